//! Möbius transformations and their optimization (Jin et al. 2004, §3.4): `maps.rs` the
//! transformations of the sphere and the disk, `energy.rs` the area energies (Eq. 1–4, 7, 8,
//! 10), `objective.rs` those energies of a boosted map with analytic gradients, `newton.rs`
//! the small damped Newton minimizer, `locality.rs` the cache-friendly
//! numbering its evaluations run on, `optimize.rs` the multistart optimization of a sphere
//! or disk map, `options.rs` its options.

pub(crate) mod energy;
pub(crate) mod locality;
pub(crate) mod maps;
pub(crate) mod newton;
pub(crate) mod objective;
pub(crate) mod optimize;
pub(crate) mod options;
