#pragma once
// Spectral sunlight: the extraterrestrial solar spectrum attenuated along the direct beam, as in
// Preetham, Shirley, Smits (1999), "A practical analytic model for daylight", Appendices A.4/A.5
// (after Iqbal, "An Introduction to Solar Radiation", 1983), integrated against the CIE 1931
// 2-degree observer into photometric XYZ.
#include <Eigen/Core>

namespace fenestra {

// Relative optical air mass of the direct beam (Kasten 1966, the form Preetham uses):
// m = 1 / (cos z + 0.15 (93.885 - z[deg])^-1.253); finite up to the horizon (m = 36.5 at z = 90 deg).
double relative_air_mass(double sun_zenith_rad);

// Extraterrestrial solar spectral radiance averaged over the disk, W/(m^2 sr nm), tabulated every
// 10 nm over 380-750 nm (zero outside).
double extraterrestrial_solar_radiance(double lambda_nm);

// Direct-beam transmittance at lambda_nm through `air_mass` atmospheres: Rayleigh scattering,
// Angstrom aerosol (beta from turbidity, alpha = 1.3), ozone (0.35 cm), uniformly mixed gases and
// water vapour (2 cm precipitable). air_mass = 0 gives 1.
double direct_beam_transmittance(double lambda_nm, double turbidity, double air_mass);

// CIE 1931 XYZ of the disk radiance after `air_mass` atmospheres (0: outside the atmosphere);
// Y is luminance in cd/m^2 (683 lm/W times the integral of radiance times y-bar).
Eigen::Vector3d solar_disk_xyz(double turbidity, double air_mass);

}  // namespace fenestra
