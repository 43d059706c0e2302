#pragma once
// The two files an `OUT[.npz]` argument names: OUT.npz (arrays) and OUT.json (summary), as
// `fenestra contributions` and `annual` write them.
#include <string>
#include <utility>

namespace fenestra {

// {OUT.npz, OUT.json} for OUT or OUT.npz. Throws std::invalid_argument when OUT as given is a
// device, FIFO, socket or directory, or OUT.npz's OUT a device, FIFO or socket: the pair would be
// created beside it (`-o /dev/null` would write /dev/null.npz), not where the user meant.
std::pair<std::string, std::string> npz_json_pair(const std::string& out);

}  // namespace fenestra
