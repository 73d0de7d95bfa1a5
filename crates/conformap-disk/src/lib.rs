//! Disk conformal maps for conformap: Angenent initial map, harmonic extension, CEM and CCEM.
