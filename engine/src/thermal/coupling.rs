//! Staggered thermo-mechanical coupling (isothermal split), the default and
//! only scheme: each increment
//! 1. solves the mechanics at the temperatures of the last converged
//!    increment (their thermal strains are fixed during the Newton loop);
//! 2. once the mechanics has converged, solves heat conduction on the
//!    converged state with
//!    - the contact conductances of the converged contact state (the same
//!      gaps and pressures that gave the contact forces),
//!    - the heat generated during the increment: plastic dissipation
//!      `beta q d(ep) dV` at each integration point (Taylor-Quinney factor
//!      `beta`), distributed to the nodes by the shape functions, and the
//!      frictional dissipation `-R_T ds` of each contact node of a pair with
//!      a `thermal` block (`NodeFriction::dissipation`, the friction work
//!      `mu R_N |ds|` when sliding), the share `friction_split` to the slave
//!      node, the rest to the master segment's nodes (`1 - xi`, `xi`) or to
//!      the rigid tool (whose temperature is prescribed: that heat leaves
//!      the model);
//! 3. updates the thermal strains used by the next increment.

use super::boundary::facet_integrals;
use super::contact::{node_conductance, ConductanceElement, ThermalMaster};
use super::contact_faces;
use super::expansion::{cell_temperatures, cell_thermal_strains};
use super::properties::{is_temperature_dependent, law_at};
use super::solver::{ThermalIncrement, ThermalSolver};
use crate::contact::face_integrated::FacetRule;
use crate::contact::NodeContact;
use crate::element::MaterialPoint;
use crate::geom::Dimension;
use crate::material::{von_mises, NonlinearLaw};
use crate::mesh::Facet;
use crate::model::thermal::ThermalScene;
use crate::model::Model;
use nalgebra::Const;

/// The thermal side of a coupled run.
#[derive(Debug, Clone)]
pub struct Coupling {
    /// Heat conduction solver and temperatures.
    pub solver: ThermalSolver,
    /// Tributary area of each slave node, per pair (the mechanical ones).
    tributary: Vec<Vec<f64>>,
    /// Per pair: the face rule of a quadratic slave body against a tool
    /// (its exchange is integrated at the faces' points,
    /// [`super::contact_faces`]), else `None`.
    faces: Vec<Option<FacetRule>>,
    /// Heat generated at each node during the last increment (energy).
    pub source: Vec<f64>,
    /// Plastic dissipation of the last increment turned into heat (energy).
    pub plastic_heat: f64,
    /// Conductance elements of the last increment (pair, element).
    pub elements: Vec<(usize, ConductanceElement)>,
}

impl Coupling {
    /// The coupling of `model`, `None` when the scene has no thermal part.
    pub fn new<const D: usize>(model: &Model<D>) -> Result<Option<Self>, String>
    where
        Const<D>: Dimension<D>,
    {
        let Some(solver) = ThermalSolver::new(model)? else {
            return Ok(None);
        };
        let tributary = (0..model.contacts.len())
            .map(|p| pair_areas(model, p))
            .collect();
        // the face rules of the thermal pairs only
        let thermal = |p: usize| {
            model
                .thermal
                .as_ref()
                .is_some_and(|t| matches!(t.contacts.get(p), Some(Some(_))))
        };
        let faces = (0..model.contacts.len())
            .map(|p| {
                thermal(p)
                    .then(|| contact_faces::pair_rule(model, p))
                    .flatten()
            })
            .collect();
        Ok(Some(Coupling {
            source: vec![0.0; solver.active.len()],
            solver,
            tributary,
            faces,
            plastic_heat: 0.0,
            elements: Vec::new(),
        }))
    }

    /// Thermal strain of every cell at the committed temperatures (what the
    /// next mechanical increment uses).
    pub fn thermal_strains<const D: usize>(&self, model: &Model<D>) -> Vec<f64> {
        match model.thermal.as_ref() {
            Some(scene) => cell_thermal_strains(model, scene, self.solver.committed()),
            None => vec![0.0; model.mesh.cells.len()],
        }
    }

    /// Law of each cell at its committed temperature for the
    /// temperature-dependent materials (empty when there are none).
    pub fn cell_laws<const D: usize>(
        &self,
        model: &Model<D>,
    ) -> Result<Vec<Option<NonlinearLaw>>, String> {
        let Some(scene) = model.thermal.as_ref() else {
            return Ok(Vec::new());
        };
        let mut out: Vec<Option<NonlinearLaw>> = Vec::new();
        let temps = cell_temperatures(model, scene, self.solver.committed());
        for body in &model.bodies {
            let Some(Some(m)) = scene.materials.get(body.material) else {
                continue;
            };
            let material = &model.materials[body.material];
            if !is_temperature_dependent(m, &material.law) {
                continue;
            }
            let Some(law) = NonlinearLaw::build(material, body.kinematics, model.analysis.kind)?
            else {
                return Err(format!(
                    "material `{}`: temperature-dependent moduli need a nonlinear law \
                     (plastic, or kinematics = finite)",
                    material.name
                ));
            };
            if out.is_empty() {
                out = vec![None; model.mesh.cells.len()];
            }
            for c in body.cells.clone() {
                out[c] = Some(law_at(&law, m, temps[c]));
            }
        }
        Ok(out)
    }

    /// Heat step of the increment ending at `t` (size `dt`), after the
    /// mechanics converged: `contact` is the converged contact state of
    /// each pair, `before`/`after` the integration points at the start and
    /// end of the increment.
    pub fn heat_step<const D: usize>(
        &mut self,
        model: &Model<D>,
        t: f64,
        dt: f64,
        contact: &[Vec<NodeContact<D>>],
        before: &[Vec<MaterialPoint>],
        after: &[Vec<MaterialPoint>],
    ) -> Result<&ThermalIncrement, String> {
        let scene = model.thermal.as_ref().ok_or("no thermal part")?;
        self.source.fill(0.0);
        self.plastic_heat = plastic_heat(model, scene, before, after, &mut self.source);
        let friction = friction_heat(model, scene, contact, &mut self.source);
        self.elements = contact_elements(model, scene, contact, &self.tributary, &self.faces, t);
        self.solver
            .solve_increment(model, t, dt, &self.elements, &self.source)?;
        self.solver.last.plastic = self.plastic_heat;
        self.solver.last.friction = friction;
        Ok(&self.solver.last)
    }
}

/// Tributary area `int N_a dA` of each slave node of pair `pair`, in
/// `ContactPair::nodes` order, from its slave facets (planar edges: the
/// rules of `contact::tributary`; solid faces: the face quadrature), in the
/// reference configuration.
pub fn pair_areas<const D: usize>(model: &Model<D>, pair: usize) -> Vec<f64> {
    let Some(cp) = model.contacts.get(pair) else {
        return Vec::new();
    };
    let mut area = vec![0.0; cp.nodes.len()];
    let edges = cp.edges.iter().map(|e| Facet::new(e));
    for facet in edges.chain(cp.faces.iter().copied()) {
        let w = facet_integrals(model, &facet).weights;
        for (node, wa) in facet.nodes().iter().zip(w) {
            if let Ok(i) = cp.nodes.binary_search(node) {
                area[i] += wa;
            }
        }
    }
    area
}

/// Conductance elements of the converged contact state (pairs with a
/// thermal block only): per slave node, or per integration point for the
/// pairs with a face rule in `faces` ([`contact_faces::face_elements`]).
pub fn contact_elements<const D: usize>(
    model: &Model<D>,
    scene: &ThermalScene,
    contact: &[Vec<NodeContact<D>>],
    tributary: &[Vec<f64>],
    faces: &[Option<FacetRule>],
    t: f64,
) -> Vec<(usize, ConductanceElement)> {
    let mut out = Vec::new();
    for (p, nodes) in contact.iter().enumerate() {
        let Some(Some(settings)) = scene.contacts.get(p) else {
            continue;
        };
        let cp = &model.contacts[p];
        let tool_temperature = match (cp.master.tool(), &settings.tool_temperature) {
            (Some(_), Some(f)) => Some(f.eval(t)),
            (Some(_), None) => continue, // adiabatic tool
            (None, _) => None,
        };
        if let (Some(Some(rule)), Some(tt)) = (faces.get(p), tool_temperature) {
            let elements = contact_faces::face_elements(rule, settings, nodes, tt);
            out.extend(elements.into_iter().map(|e| (p, e)));
            continue;
        }
        for c in nodes {
            let Ok(i) = cp.nodes.binary_search(&c.node) else {
                continue;
            };
            let area = tributary[p].get(i).copied().unwrap_or(0.0);
            let h = node_conductance(settings, c);
            if h * area == 0.0 {
                continue;
            }
            let master = match (tool_temperature, c.master) {
                (Some(tt), _) => ThermalMaster::Tool(tt),
                (None, Some(seg)) => ThermalMaster::Segment {
                    nodes: seg.nodes,
                    xi: seg.xi,
                },
                (None, None) => continue,
            };
            out.push((p, ConductanceElement::new(c.node, h * area, master)));
        }
    }
    out
}

/// Frictional dissipation of the thermal pairs during the increment, split
/// between the slave node and the master segment (the tool's share leaves
/// the model), added to the nodal sources `out` (energy); returns the total
/// dissipation.
pub fn friction_heat<const D: usize>(
    model: &Model<D>,
    scene: &ThermalScene,
    contact: &[Vec<NodeContact<D>>],
    out: &mut [f64],
) -> f64 {
    let mut total = 0.0;
    for (p, nodes) in contact.iter().enumerate() {
        let Some(Some(settings)) = scene.contacts.get(p) else {
            continue;
        };
        if model.contacts.get(p).is_none_or(|c| c.friction.is_none()) {
            continue;
        }
        let split = settings.friction_split;
        for c in nodes {
            let d = c.friction.dissipation;
            if d == 0.0 {
                continue;
            }
            total += d;
            out[c.node] += split * d;
            if let Some(seg) = &c.master {
                out[seg.nodes[0]] += (1.0 - split) * (1.0 - seg.xi) * d;
                out[seg.nodes[1]] += (1.0 - split) * seg.xi * d;
            }
        }
    }
    total
}

/// Plastic dissipation turned into heat during the increment, added to the
/// nodal sources `out` (energy); returns the total.
pub fn plastic_heat<const D: usize>(
    model: &Model<D>,
    scene: &ThermalScene,
    before: &[Vec<MaterialPoint>],
    after: &[Vec<MaterialPoint>],
    out: &mut [f64],
) -> f64 {
    let mut total = 0.0;
    for body in &model.bodies {
        let Some(Some(m)) = scene.materials.get(body.material) else {
            continue;
        };
        if m.taylor_quinney == 0.0 {
            continue;
        }
        for c in body.cells.clone() {
            let (Some(b), Some(a)) = (before.get(c), after.get(c)) else {
                continue;
            };
            let cell = model.mesh.cells.get(c);
            for (k, (pb, pa)) in b.iter().zip(a).enumerate() {
                let dep = pa.history.ep - pb.history.ep;
                if dep <= 0.0 {
                    continue;
                }
                let q = von_mises(&pa.state.stress);
                let heat = m.taylor_quinney * q * dep * pa.state.volume;
                total += heat;
                let n = crate::element::reference::quadrature_shape(cell.kind, k);
                for (na, &node) in n.iter().zip(cell.nodes) {
                    out[node] += na * heat;
                }
            }
        }
    }
    total
}
