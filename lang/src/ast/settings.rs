//! Typed values of a block read through a key table ([`crate::keys`]):
//! the settings of a mesh generator.

use super::items::MeshDef;
use super::values::Grading;
use crate::keys::{Default, Key};
use crate::span::{Span, Spanned};

/// A value read by its key's type.
#[derive(Debug, Clone, PartialEq)]
pub enum SettingValue {
    /// [`crate::keys::KeyType::Number`].
    Number(f64),
    /// [`crate::keys::KeyType::Integer`].
    Integer(i64),
    /// [`crate::keys::KeyType::Bool`].
    Bool(bool),
    /// [`crate::keys::KeyType::Choice`]: the name chosen.
    Choice(&'static str),
    /// [`crate::keys::KeyType::Point`] and [`crate::keys::KeyType::Numbers`]:
    /// 2 or 3 components, each with its span.
    Numbers(Vec<Spanned<f64>>),
    /// [`crate::keys::KeyType::Integers`].
    Integers(Vec<Spanned<i64>>),
    /// [`crate::keys::KeyType::Grading`].
    Grading(Grading),
    /// [`crate::keys::KeyType::Gradings`].
    Gradings(Vec<Spanned<Grading>>),
    /// [`crate::keys::KeyType::Mesh`]: the input mesh of a generator.
    Mesh(Box<Spanned<MeshDef>>),
    /// [`crate::keys::KeyType::File`]: the path as written.
    Text(String),
}

/// One key given in the deck, with its value.
#[derive(Debug, Clone, PartialEq)]
pub struct Setting {
    /// The key's table entry.
    pub key: &'static Key,
    /// The value and where it was written.
    pub value: Spanned<SettingValue>,
}

/// The keys of a block that were given and parsed, in table order.
/// Accessors fall back to the table's default when a key is left out.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Settings {
    /// The settings given.
    pub entries: Vec<Setting>,
}

impl Settings {
    /// The setting of `key`, if given.
    pub fn get(&self, key: &str) -> Option<&Setting> {
        self.entries.iter().find(|s| s.key.name == key)
    }

    /// Whether `key` was given.
    pub fn has(&self, key: &str) -> bool {
        self.get(key).is_some()
    }

    /// Span of the value of `key`, if given.
    pub fn span(&self, key: &str) -> Option<Span> {
        self.get(key).map(|s| s.value.span)
    }

    fn default_of(&self, key: &str, table: &[Key]) -> Default {
        table
            .iter()
            .find(|k| k.name == key)
            .map_or(Default::None, |k| k.default)
    }

    /// A number (given, or the default of `table`).
    pub fn number(&self, key: &str, table: &[Key]) -> Option<f64> {
        match self.get(key).map(|s| &s.value.value) {
            Some(SettingValue::Number(x)) => Some(*x),
            _ => match self.default_of(key, table) {
                Default::Number(x) => Some(x),
                _ => None,
            },
        }
    }

    /// A number as given, with its span (no default).
    pub fn spanned_number(&self, key: &str) -> Option<Spanned<f64>> {
        let s = self.get(key)?;
        match s.value.value {
            SettingValue::Number(x) => Some(Spanned::new(x, s.value.span)),
            _ => None,
        }
    }

    /// A whole number (given, or the default).
    pub fn integer(&self, key: &str, table: &[Key]) -> Option<i64> {
        match self.get(key).map(|s| &s.value.value) {
            Some(SettingValue::Integer(n)) => Some(*n),
            _ => match self.default_of(key, table) {
                Default::Integer(n) => Some(n),
                _ => None,
            },
        }
    }

    /// A whole number as given, with its span (no default).
    pub fn spanned_integer(&self, key: &str) -> Option<Spanned<i64>> {
        let s = self.get(key)?;
        match s.value.value {
            SettingValue::Integer(n) => Some(Spanned::new(n, s.value.span)),
            _ => None,
        }
    }

    /// A boolean (given, or the default).
    pub fn bool(&self, key: &str, table: &[Key]) -> Option<bool> {
        match self.get(key).map(|s| &s.value.value) {
            Some(SettingValue::Bool(b)) => Some(*b),
            _ => match self.default_of(key, table) {
                Default::Bool(b) => Some(b),
                _ => None,
            },
        }
    }

    /// A choice (given, or the default).
    pub fn choice(&self, key: &str, table: &[Key]) -> Option<&'static str> {
        match self.get(key).map(|s| &s.value.value) {
            Some(SettingValue::Choice(c)) => Some(*c),
            _ => match self.default_of(key, table) {
                Default::Choice(c) => Some(c),
                _ => None,
            },
        }
    }

    /// The components of a point or number tuple (given, or the default).
    pub fn numbers(&self, key: &str, table: &[Key]) -> Option<Vec<f64>> {
        match self.get(key).map(|s| &s.value.value) {
            Some(SettingValue::Numbers(xs)) => Some(xs.iter().map(|x| x.value).collect()),
            _ => match self.default_of(key, table) {
                Default::Numbers(xs) => Some(xs.to_vec()),
                _ => None,
            },
        }
    }

    /// A 2-component point or tuple.
    pub fn pair(&self, key: &str, table: &[Key]) -> Option<[f64; 2]> {
        let v = self.numbers(key, table)?;
        (v.len() == 2).then(|| [v[0], v[1]])
    }

    /// The components of a whole-number tuple, as given.
    pub fn integers(&self, key: &str) -> Option<Vec<i64>> {
        match self.get(key).map(|s| &s.value.value) {
            Some(SettingValue::Integers(ns)) => Some(ns.iter().map(|n| n.value).collect()),
            _ => None,
        }
    }

    /// A grading (given, or uniform).
    pub fn grading(&self, key: &str) -> Grading {
        match self.get(key).map(|s| &s.value.value) {
            Some(SettingValue::Grading(g)) => g.clone(),
            _ => Grading::Uniform,
        }
    }

    /// The gradings of a tuple (given, or `n` times uniform).
    pub fn gradings(&self, key: &str, n: usize) -> Vec<Grading> {
        match self.get(key).map(|s| &s.value.value) {
            Some(SettingValue::Gradings(gs)) => gs.iter().map(|g| g.value.clone()).collect(),
            _ => vec![Grading::Uniform; n],
        }
    }

    /// An input mesh, as given.
    pub fn mesh(&self, key: &str) -> Option<&Spanned<MeshDef>> {
        match self.get(key).map(|s| &s.value.value) {
            Some(SettingValue::Mesh(m)) => Some(m),
            _ => None,
        }
    }
}
