//! End-to-end tests of `rollfit report` (being written).
