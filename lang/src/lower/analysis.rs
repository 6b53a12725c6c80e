//! The `analysis` block -> `model::Analysis`.

use super::Lowerer;
use crate::ast::{Dimension, Span};
use ctc_engine::model::{Analysis, AnalysisKind};

impl Lowerer<'_> {
    pub(super) fn analysis(&mut self) -> Option<Analysis> {
        let Some(a) = self.deck.analysis.first() else {
            self.missing("the analysis block", Span::default());
            return None;
        };
        let kind = match a.dimension.as_ref().map(|d| d.value) {
            Some(Dimension::PlaneStrain) => AnalysisKind::PlaneStrain,
            Some(Dimension::PlaneStress) => AnalysisKind::PlaneStress,
            Some(Dimension::Axisymmetric) => AnalysisKind::Axisymmetric,
            Some(Dimension::ThreeD) => AnalysisKind::Solid,
            None => {
                self.missing("a supported dimension", a.keyword);
                return None;
            }
        };
        let thickness = match kind {
            AnalysisKind::Axisymmetric | AnalysisKind::Solid => 1.0,
            _ => a.thickness.as_ref().map_or(1.0, |t| t.value),
        };
        Some(Analysis { kind, thickness })
    }
}
