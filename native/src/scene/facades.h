#pragma once
// Which panels of the opening domain are walls, and which walls form one facade (the coplanar
// flat wall panels): sill and head limits, window catalogues and facade rules read them.
#include <vector>

#include "scene/opening_domain.h"

namespace fenestra {

// Panels whose normal lies within 30 degrees of horizontal: sill and head limits apply there.
bool is_wall(const Panel& panel);

// Per panel, its facade's index (coplanar flat walls, within kPlaneTolerance), or -1 (roofs, curved panels).
std::vector<int> facades_of(const OpeningDomain& domain);

}  // namespace fenestra
