//! ctc-verification: verification cases of ctc.

pub mod analytical;
pub mod refine;
pub mod capture;
pub mod profile;
pub mod case;
pub mod measure;
