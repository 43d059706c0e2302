#include "scene/site_frame.h"

#include <cmath>
#include <sstream>

namespace fenestra {

SiteFrame SiteFrame::around(const Vec3d& lo, const Vec3d& hi) {
  SiteFrame frame;
  if (lo.cwiseAbs().maxCoeff() <= kNearOrigin && hi.cwiseAbs().maxCoeff() <= kNearOrigin) return frame;
  // floor(c + 0.5) rather than round(): half-metre centres move with the model (round(-0.5) = -1,
  // round(999999.5) = 1000000).
  for (int k = 0; k < 3; ++k) frame.origin[k] = std::floor(0.5 * (lo[k] + hi[k]) + 0.5);
  return frame;
}

std::string SiteFrame::to_string() const {
  std::ostringstream s;
  s.precision(17);
  s << "SiteFrame(origin=[" << origin.x() << ", " << origin.y() << ", " << origin.z() << "] m)";
  return s.str();
}

}  // namespace fenestra
