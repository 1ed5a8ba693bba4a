//! End-to-end tests of `rollfit compare` (being written).
