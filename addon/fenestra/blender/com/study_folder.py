"""The study folder, replaced only by a solve that succeeded: a solve writes its study into a hidden
folder beside it and solves from there; on success that folder takes the study folder's place in
one step, and the files it does not write (a previewed sky.exr, the user's own) are carried over.
A refused, failed or cancelled solve deletes its folder and leaves the previous study (scene.json,
scene.obj and result.json, which belong together) as it was. No bpy here."""

import ctypes
import errno
import os
import shutil
import tempfile

STUDY_FILES = ("scene.json", "scene.obj", "result.json")  # what a solve writes; the rest is carried over


def _libc_renameat2():
    try:
        function = ctypes.CDLL(None, use_errno=True).renameat2
    except (AttributeError, OSError, TypeError):
        return None
    function.argtypes = [ctypes.c_int, ctypes.c_char_p, ctypes.c_int, ctypes.c_char_p, ctypes.c_uint]
    return function


_renameat2 = _libc_renameat2()
_AT_FDCWD, _RENAME_EXCHANGE = -100, 2


def _exchange(a, b):
    """Swaps two folders: in one step where the system can (Linux), else by two renames."""
    if _renameat2 is not None:
        if _renameat2(_AT_FDCWD, os.fsencode(a), _AT_FDCWD, os.fsencode(b), _RENAME_EXCHANGE) == 0:
            return
        code = ctypes.get_errno()
        if code not in (errno.EINVAL, errno.ENOSYS, errno.ENOTSUP):
            raise OSError(code, os.strerror(code), b)
    aside = tempfile.mkdtemp(prefix=".%s.previous-" % os.path.basename(b), dir=os.path.dirname(b))
    os.rename(b, aside)  # onto an empty folder: replaces it
    try:
        os.rename(a, b)
    except OSError:
        os.rename(aside, b)
        raise
    os.rename(aside, a)


class StagingFolder:
    """Where a solve writes its study until it succeeds; `path` is that folder. `written` names the
    files the new folder replaces (an Annual Daylight run stages its own folder with its own files);
    the previous folder's other files are carried over."""

    def __init__(self, study_directory, written=STUDY_FILES):
        self.written = tuple(written)
        # Through a symbolic link: the folder it points to is the one replaced.
        self.final = os.path.realpath(study_directory)
        if os.path.exists(self.final) and not os.path.isdir(self.final):
            raise OSError(errno.ENOTDIR, "The study folder is a file: choose a folder in Solve > Study Folder",
                          self.final)
        parent, name = os.path.split(self.final)
        os.makedirs(parent, exist_ok=True)
        self.path = tempfile.mkdtemp(prefix=".%s.solving-" % name, dir=parent)

    def commit(self):
        """Moves the study into place. Returns None, or the hidden folder where files of the
        previous study folder stayed when they could not be carried over (nothing is deleted)."""
        if not os.path.isdir(self.final):
            os.rename(self.path, self.final)
            return None
        _exchange(self.path, self.final)
        previous = self.path  # now the previous study folder
        try:
            for name in os.listdir(previous):
                if name not in self.written:
                    os.rename(os.path.join(previous, name), os.path.join(self.final, name))
            for name in self.written:
                if os.path.lexists(os.path.join(previous, name)):
                    os.remove(os.path.join(previous, name))
            os.rmdir(previous)
        except OSError:
            return previous
        return None

    def discard(self):
        shutil.rmtree(self.path, ignore_errors=True)
