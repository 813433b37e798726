//! Physical constants (CODATA 2018, exact SI definitions since 2019) and the conventional
//! wavelength range.

/// Planck constant h, J s (exact).
pub const PLANCK: f64 = 6.626_070_15e-34;
/// Speed of light in vacuum c, m/s (exact).
pub const SPEED_OF_LIGHT: f64 = 299_792_458.0;
/// Boltzmann constant k_B, J/K (exact).
pub const BOLTZMANN: f64 = 1.380_649e-23;
/// Elementary charge e, C (exact); one electronvolt is this many joules.
pub const ELEMENTARY_CHARGE: f64 = 1.602_176_634e-19;
/// Wien's displacement constant b = h c / (k_B x), x the root of x = 5 (1 - e^-x), in m K.
/// Derived from the exact constants above (CODATA 2018 lists 2.897 771 955e-3).
pub const WIEN_DISPLACEMENT: f64 = PLANCK * SPEED_OF_LIGHT / (BOLTZMANN * WIEN_X);
/// Root of x = 5 (1 - e^-x), the dimensionless peak of Planck's law in wavelength.
pub(crate) const WIEN_X: f64 = 4.965_114_231_744_276;
/// Maximum luminous efficacy of photopic vision K_m, lm/W (CIE 015:2018, rounded as the
/// issue and colour-science use it).
pub const LUMINOUS_EFFICACY_MAX: f64 = 683.0;

/// Shortest wavelength of the CIE colour-matching-function tables, nm.
pub const LAMBDA_MIN: f64 = 360.0;
/// Longest wavelength of the CIE colour-matching-function tables, nm.
pub const LAMBDA_MAX: f64 = 830.0;
