//! What a form's reader ([`super::csv_form`], [`super::trios`]) hands to the
//! checks every form shares ([`super::checks`]).

use super::point::ModulusKind;
use crate::error::ColumnRef;

/// One point as a reader found it, before the checks common to all forms.
pub(crate) struct RawPoint {
    /// Line in the file, counting from 1.
    pub line: usize,
    /// rad/s.
    pub omega: f64,
    /// Pa, shear or Young's as the file says.
    pub storage: f64,
    /// Pa.
    pub loss: f64,
    /// °C.
    pub temperature: Option<f64>,
}

/// The columns (or variables) of the three moduli fields, for messages.
pub(crate) struct FieldNames {
    pub omega: ColumnRef,
    pub storage: ColumnRef,
    pub loss: ColumnRef,
}

/// What a form's reader found: the points before the common checks.
pub(crate) struct FormRead {
    pub points: Vec<RawPoint>,
    pub kind: ModulusKind,
    pub names: FieldNames,
    pub warnings: Vec<String>,
}
