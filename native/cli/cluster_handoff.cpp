#include "cluster_handoff.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace fenestra {

bool wants_cluster(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--workers" || arg == "--scheduler" || arg == "--shards") return true;
  }
  return false;
}

int hand_to_cluster(int argc, char** argv) {
  const char* python = std::getenv("FENESTRA_PYTHON");
  if (!python || !*python) python = FENESTRA_PYTHON;
  const char* addon = std::getenv("FENESTRA_ADDON_DIR");
  if (!addon || !*addon) addon = FENESTRA_ADDON_DIR;
  const char* old_path = std::getenv("PYTHONPATH");
  const std::string path = std::string(addon) + (old_path && *old_path ? std::string(":") + old_path : "");
  setenv("PYTHONPATH", path.c_str(), 1);
  std::vector<char*> args = {const_cast<char*>(python), const_cast<char*>("-m"),
                             const_cast<char*>("fenestra.distributed_cli")};
  for (int i = 1; i < argc; ++i) args.push_back(argv[i]);
  args.push_back(nullptr);
  execv(python, args.data());
  std::fprintf(stderr, "fenestra: error: cannot start %s for a run on a Dask cluster: %s (set FENESTRA_PYTHON)\n",
               python, std::strerror(errno));
  return 1;
}

}  // namespace fenestra
