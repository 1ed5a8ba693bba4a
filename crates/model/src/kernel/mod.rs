//! Universal kernels of the friction integrals. PLACEHOLDER while written.
