//! End-to-end and real-mesh tests of the conformap workspace; the tests live in `tests/`.
