//! The film sphere kernel (work in progress).
pub mod blend;
pub mod integrals;
pub mod moments;
pub mod rows;
