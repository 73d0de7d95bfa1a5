//! Quality metrics of planar conformal maps: conformal energy, angle distortion, Beltrami coefficient, area distortion, flips.
