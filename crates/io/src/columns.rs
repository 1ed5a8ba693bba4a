//! Column names that one part of rollfit writes and another reads, or that
//! two readers share, beyond the fit folder's own
//! ([`crate::fit_dir::columns`], whose `v`, `sigma`, `T` and `mu_measured`
//! the measured-data reader takes too, and whose `omega`, `E_storage`,
//! `E_loss` and `T` the DMA and modulus-table readers do): defined once, so
//! that a writer and its readers cannot drift apart (docs/ARCHITECTURE.md,
//! "Contract": extend them, do not rename what exists).

/// The friction coefficient μ: the canonical column of measured data
/// ("Measured data"), written by `rollfit forward` ("Forward CSV") and read
/// by [`crate::data`].
pub const MU: &str = "mu";

/// The frequency a point of master.csv was measured at, rad/s, before its
/// shift (`rollfit master` output, "master.csv"). The modulus-table reader
/// ([`crate::table`]) recognises master.csv by it.
pub const OMEGA_MEASURED: &str = "omega_measured";

/// The frequency column in hertz of a DMA file or modulus table.
pub const F: &str = "f";
/// The shear storage modulus column of a DMA file (G′, Pa).
pub const G_STORAGE: &str = "G_storage";
/// The shear loss modulus column of a DMA file (G″, Pa).
pub const G_LOSS: &str = "G_loss";

/// The time column of a stress-relaxation file and of the master.csv
/// `rollfit master` writes from one, s (reduced t/a_T there).
pub const TIME: &str = "t";
/// The time a relaxation point was measured at, s, before its shift
/// (master.csv of a relaxation file).
pub const TIME_MEASURED: &str = "t_measured";
/// The Young's relaxation modulus E(t) of a relaxation file and of its
/// master.csv, Pa.
pub const E_RELAX: &str = "E_relax";
/// The shear relaxation modulus G(t) of a relaxation file, Pa.
pub const G_RELAX: &str = "G_relax";
/// The tensile creep compliance D(t) of a creep file and of the master.csv
/// and creep.csv `rollfit master` writes from one, 1/Pa.
pub const D_CREEP: &str = "D_creep";
/// The shear creep compliance J(t) of a creep file, 1/Pa.
pub const J_CREEP: &str = "J_creep";
