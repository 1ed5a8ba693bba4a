//! The cell tables of the grids solved last, shared by every solve of
//! the process.
//!
//! A [`CellTable`] (the elastic influence C(X, Y) of a cell and its
//! samples at the product-integration nodes, [`super::memory`]) depends on
//! the grid's shape nx × ny, the element and the quadrature order only —
//! not on the speed, the material or the cell size, which enter through
//! the memory lengths ℓ_j = vλ_j/h and the weights of
//! A = J0 C + Σ_j c_j M(ℓ_j). The three grids of every speed at one
//! accuracy have the same few shapes (the extent grows only where the
//! contact reaches the border), so a sweep of speeds, and the sweeps of a
//! fit, build each table once instead of once per solve. Building one
//! costs (2nx + 1)(ny + 1)(2q + 1) corner functions (logarithms), about a
//! tenth of a solve. The cache returns the same table a fresh build
//! would, so results do not depend on it.
//!
//! # References
//!
//! - K.L. Johnson, *Contact Mechanics*, Cambridge University Press 1985,
//!   §3.9 (the influence of a uniformly loaded rectangle).

use std::sync::{Arc, Mutex};

use super::element::Element;
use super::memory::CellTable;

/// The table of an nx × ny grid of `element` with `order` nodes per half
/// cell: from the list of the tables used last (newest first), or built
/// and put at its head.
pub(crate) fn cell_table(nx: usize, ny: usize, order: usize, element: Element) -> Arc<CellTable> {
    static CACHE: Mutex<Vec<Arc<CellTable>>> = Mutex::new(Vec::new());
    let find = |cache: &mut Vec<Arc<CellTable>>| {
        let at = cache
            .iter()
            .position(|t| (t.nx, t.ny, t.order(), t.element()) == (nx, ny, order, element))?;
        let table = cache.remove(at);
        cache.insert(0, table.clone());
        Some(table)
    };
    // A poisoned lock only means another solve panicked mid-update of a
    // list of complete tables: the list is still valid.
    let lock = || CACHE.lock().unwrap_or_else(|e| e.into_inner());
    if let Some(table) = find(&mut lock()) {
        return table;
    }
    // Built outside the lock: parallel solves may build the same table
    // twice at first, but never wait on each other's build.
    let table = Arc::new(CellTable::new(nx, ny, order, element));
    let mut cache = lock();
    cache.insert(0, table.clone());
    cache.truncate(CACHED_TABLES);
    table
}

/// Tables kept by [`cell_table`]: the three grids of one accuracy, grown
/// grids and a second accuracy (a fit's first sweep is coarser) fit; a
/// 144-cell grid's table is about 9 MB.
const CACHED_TABLES: usize = 12;
