"""Gives the wheel's vendored Embree its own symbol names: every rtc* function the renamed
libembree3-<hash>.so defines becomes fenestra_rtc*, in that library and in the modules and program
that call it (patchelf --rename-dynamic-symbols), and the wheel's RECORD is rewritten.

Why: a host process whose own libraries are global (Blender's executable links libembree4.so.4)
would otherwise capture _core's calls to rtcNewDevice, rtcIntersect1, ... (Embree 4 keeps Embree 3's
names): the dynamic linker searches the global scope first, and the rays silently go wrong. Renaming
the file (auditwheel) keeps the two libraries apart; renaming the symbols keeps the calls apart.

    python scripts/rename_embree_symbols.py WHEEL PATCHELF
"""

import base64
import hashlib
import os
import subprocess
import sys
import tempfile
import zipfile

from elftools.elf.elffile import ELFFile  # auditwheel's dependency, in the packaging venv

PREFIX = "fenestra_"


def dynamic_symbols(path, defined):
    with open(path, "rb") as f:
        elf = ELFFile(f)
        table = elf.get_section_by_name(".dynsym")
        if table is None:
            return set()
        return {s.name for s in table.iter_symbols()
                if s.name.startswith("rtc") and (s["st_shndx"] != "SHN_UNDEF") == defined}


def is_elf(path):
    with open(path, "rb") as f:
        return f.read(4) == b"\x7fELF"


def record_line(root, name):
    with open(os.path.join(root, name), "rb") as f:
        data = f.read()
    digest = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
    return "%s,sha256=%s,%d" % (name, digest, len(data))


def main(wheel, patchelf):
    with tempfile.TemporaryDirectory() as root:
        with zipfile.ZipFile(wheel) as z:
            names = z.namelist()
            z.extractall(root)
            modes = {i.filename: i.external_attr for i in z.infolist()}
        embree = [n for n in names if os.path.basename(n).startswith("libembree")]
        if len(embree) != 1:
            sys.exit("rename_embree_symbols: expected one vendored Embree in %s, found %s" % (wheel, embree))
        symbols = dynamic_symbols(os.path.join(root, embree[0]), defined=True)
        if not symbols:
            sys.exit("rename_embree_symbols: %s defines no rtc* symbol" % embree[0])
        callers = [n for n in names if not n.endswith("/") and is_elf(os.path.join(root, n)) and n != embree[0]
                   and dynamic_symbols(os.path.join(root, n), defined=False) & symbols]
        mapping = os.path.join(root, "..", os.path.basename(root) + ".map")
        with open(mapping, "w") as f:
            f.writelines("%s %s%s\n" % (s, PREFIX, s) for s in sorted(symbols))
        try:
            subprocess.run([patchelf, "--rename-dynamic-symbols", mapping] +
                           [os.path.join(root, n) for n in embree + callers], check=True)
        finally:
            os.remove(mapping)
        record = next(n for n in names if n.endswith(".dist-info/RECORD"))
        with open(os.path.join(root, record), "w") as f:
            f.writelines(record_line(root, n) + "\n" for n in names if n != record and not n.endswith("/"))
            f.write(record + ",,\n")
        part = wheel + ".part"
        with zipfile.ZipFile(part, "w", zipfile.ZIP_DEFLATED) as z:
            for n in names:
                info = zipfile.ZipInfo(n, date_time=(1980, 1, 1, 0, 0, 0))
                info.external_attr = modes[n]
                info.compress_type = zipfile.ZIP_DEFLATED
                if n.endswith("/"):
                    z.writestr(info, b"")
                    continue
                with open(os.path.join(root, n), "rb") as f:
                    z.writestr(info, f.read())
        os.replace(part, wheel)
    print("renamed %d Embree symbols in %s and %s" % (len(symbols), embree[0], ", ".join(callers)))


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(*sys.argv[1:])
