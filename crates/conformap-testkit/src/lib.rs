//! Test support for the conformap workspace: assert_near!, fixture loaders and analytic meshes (never published).
