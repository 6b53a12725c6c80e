//! Search state and counters of the face search (the engine's health
//! figures: projections per query, Newton iterations, faces tested).

use crate::Vec2;

/// What a query remembers of the previous one for the same node.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SearchState {
    /// The face that held the last foot (tested first, then its neighbours).
    pub last_face: Option<usize>,
    /// The parameter of the last foot on that face (the Newton seed).
    pub last_uv: Option<Vec2>,
    /// Search distance (`prof`): faces whose box is farther are not tested.
    pub reach: f64,
}

impl SearchState {
    /// No memory, unlimited reach.
    pub fn new() -> Self {
        SearchState {
            last_face: None,
            last_uv: None,
            reach: f64::INFINITY,
        }
    }

    /// No memory, search distance `reach`.
    pub fn with_reach(reach: f64) -> Self {
        SearchState {
            reach,
            ..SearchState::new()
        }
    }
}

impl Default for SearchState {
    fn default() -> Self {
        SearchState::new()
    }
}

/// Work counters, summed over queries.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Counters {
    /// Queries (nodes projected).
    pub queries: u64,
    /// Faces whose surface was projected on.
    pub faces_tested: u64,
    /// Faces skipped by their box (farther than the best candidate or the
    /// reach).
    pub faces_skipped: u64,
    /// Surface projections (one per face tested).
    pub surface_projections: u64,
    /// Edge projections.
    pub edge_projections: u64,
    /// Newton iterations (surfaces and edges).
    pub newton_iterations: u64,
    /// Rays drawn by the parity test (more than one per test: restarts on
    /// degenerate crossings).
    pub parity_rays: u64,
    /// Surface projections that did not converge.
    pub not_converged: u64,
}

impl Counters {
    /// Adds another set of counters.
    pub fn add(&mut self, o: &Counters) {
        self.queries += o.queries;
        self.faces_tested += o.faces_tested;
        self.faces_skipped += o.faces_skipped;
        self.surface_projections += o.surface_projections;
        self.edge_projections += o.edge_projections;
        self.newton_iterations += o.newton_iterations;
        self.parity_rays += o.parity_rays;
        self.not_converged += o.not_converged;
    }

    /// Projections (surface and edge) per query.
    pub fn projections_per_query(&self) -> f64 {
        (self.surface_projections + self.edge_projections) as f64 / self.queries.max(1) as f64
    }
}
