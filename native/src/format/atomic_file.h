#pragma once
// Output files written all at once or not at all, and checked before any work is done.
//
// Each file is first written to a temporary in its own directory: an unnamed one (O_TMPFILE)
// where the file system allows, which the kernel reclaims whatever happens to the process;
// otherwise `.NAME.fenestra-PID-N.tmp`. Once every file of a set is complete, each temporary is
// given its name (`.NAME.fenestra-PID-N.tmp`) and renamed over its target, one after the other,
// in the order given. On any failure the temporaries and the files of the set already renamed
// are removed. Only a SIGKILL (or power loss) within the final renames (microseconds) can leave
// a set incomplete or a named temporary behind; the next write into that directory removes
// temporaries whose process is gone.
//
// Outputs must be regular files or not exist yet: symbolic links, directories, devices, FIFOs
// and sockets are refused (they would be replaced by a regular file), and so is an output that
// is one of the inputs.
#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include "util/progress.h"

namespace fenestra {

using FileWriter = std::function<void(std::ostream&)>;

struct OutputFile {
  std::string path;
  FileWriter write;
};

// Throws std::invalid_argument naming `path` when it cannot be written: its directory is
// missing, not a directory or not writable; it exists and is not a regular file (a symbolic
// link, directory, device, FIFO or socket); or it is the same file as one of `inputs` (named).
void check_output_path(const std::string& path, const std::vector<std::string>& inputs = {});
// The same for each path, and no two of them the same file.
void check_output_paths(const std::vector<std::string>& paths, const std::vector<std::string>& inputs = {});

// Checks every path (check_output_paths), writes each file to its temporary, then renames them
// all into place; all or nothing. When `interrupt` is cancelled before the renames (a signal on
// the command line), nothing is renamed and Cancelled is thrown.
void write_files_atomically(const std::vector<OutputFile>& files, const std::vector<std::string>& inputs = {},
                            const Progress* interrupt = nullptr);
void write_atomically(const std::string& path, const FileWriter& write);

// The Progress whose cancellation stops every later write before its renames (the command
// line's signal handlers cancel it); null for none.
void set_write_interrupt(const Progress* interrupt);

// Removes `.NAME.fenestra-PID-N.tmp` files in `directory` whose process no longer runs.
void remove_stale_temporaries(const std::string& directory);

}  // namespace fenestra
