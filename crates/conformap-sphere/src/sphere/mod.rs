//! Sphere maps of closed genus-0 surfaces (Angenent's dipole map with corrections, Jin et
//! al. 2004 §3.4's starting point): `map.rs` the map, `source.rs` where the dipole goes,
//! `metrics.rs` the sphere map's quality, `report.rs` its report types, `untangle.rs` the
//! last step of the flip-free guard, `exact.rs` inscribed meshes and Möbius centring.

pub(crate) mod exact;
pub(crate) mod map;
pub(crate) mod metrics;
pub(crate) mod report;
pub(crate) mod source;
pub(crate) mod untangle;
