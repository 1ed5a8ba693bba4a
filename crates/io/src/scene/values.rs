//! The number types of a scene file: a finite number, a number or a list,
//! and the small checks the sections share.

use std::fmt;

use serde::Deserialize;
use serde::de::{self, Deserializer, SeqAccess, Visitor};

use crate::error::IoError;

/// A finite floating-point number from the scene file.
///
/// TOML admits `nan` and `inf`; no parameter of a scene can take them, and
/// rejecting them while deserializing lets toml report the line and column.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Real(pub f64);

pub(crate) fn finite<E: de::Error>(v: f64) -> Result<Real, E> {
    if v.is_finite() {
        Ok(Real(v))
    } else {
        Err(E::custom(format!(
            "found {v}, expected a finite number (nan and inf are not allowed)"
        )))
    }
}

impl<'de> Deserialize<'de> for Real {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct RealVisitor;
        impl Visitor<'_> for RealVisitor {
            type Value = Real;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a finite number")
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<Real, E> {
                finite(v)
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<Real, E> {
                Ok(Real(v as f64))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<Real, E> {
                Ok(Real(v as f64))
            }
        }
        deserializer.deserialize_f64(RealVisitor)
    }
}

pub(crate) fn reals(values: &[Real]) -> Vec<f64> {
    values.iter().map(|r| r.0).collect()
}

/// A key that is a number for one material model and a list for another
/// (`tau`: one time for "sls", one per term for "prony").
#[derive(Debug, Clone, PartialEq)]
pub enum RealOrList {
    /// A single number.
    One(f64),
    /// An array of numbers.
    List(Vec<f64>),
}

impl<'de> Deserialize<'de> for RealOrList {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct OneOrListVisitor;
        impl<'de> Visitor<'de> for OneOrListVisitor {
            type Value = RealOrList;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a finite number or an array of finite numbers")
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<RealOrList, E> {
                finite(v).map(|r| RealOrList::One(r.0))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<RealOrList, E> {
                Ok(RealOrList::One(v as f64))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<RealOrList, E> {
                Ok(RealOrList::One(v as f64))
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<RealOrList, A::Error> {
                let mut values = Vec::new();
                while let Some(Real(v)) = seq.next_element::<Real>()? {
                    values.push(v);
                }
                Ok(RealOrList::List(values))
            }
        }
        deserializer.deserialize_any(OneOrListVisitor)
    }
}

pub(crate) fn value_of(r: Option<Real>) -> f64 {
    r.map_or(f64::NAN, |r| r.0)
}

pub(crate) fn require_positive(key: &'static str, value: f64) -> Result<(), IoError> {
    if value > 0.0 {
        Ok(())
    } else {
        Err(err!("{key} = {value}: must be greater than zero"))
    }
}
