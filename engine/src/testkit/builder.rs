//! [`ModelBuilder`]: a model described by what it contains.
//!
//! ```
//! use ctc_engine::model::{MaterialLaw, TimeFunction};
//! use ctc_engine::testkit::{grid::grid, ModelBuilder};
//!
//! let mesh = grid(4, 2, [0.0, 0.0], [2.0, 1.0], 0.0, 1, false);
//! let model = ModelBuilder::plane_strain()
//!     .elastic("steel", 200e3, 0.3)
//!     .body("plate", mesh, "steel")
//!     .fix([0, 5, 10], 0)
//!     .fix([0], 1)
//!     .displace([4, 9, 14], 0, TimeFunction::Constant(0.01))
//!     .step("pull", 1.0, 2)
//!     .build();
//! assert_eq!(model.bodies[0].nodes, 0..15);
//! assert_eq!(model.steps[0].t_start, 0.0);
//! ```
//!
//! Bodies are appended to one global mesh in the order they are added;
//! their node and cell numbers are shifted, and their mesh sets are kept
//! under the qualified name `body.set` (as the deck's lowering does).
//! Setters without a subject (`formulation`, `friction`, `newton`, ..)
//! apply to the last body, contact pair or step added.

use crate::mesh::Mesh;
use crate::model::{
    Analysis, AnalysisKind, Body, ContactMaster, ContactMethod, ContactPair, ContactStrategy,
    Dirichlet, Formulation, Friction, Kinematics, Load, LocalSearch, Material, MaterialLaw, Model,
    NewtonSettings, OutputRequest, RigidTool, Step, TimeFunction, ToolGeometry, ToolMotion,
};

/// `v0 = 0` at `t0` to `v1` at `t1`, constant outside.
pub fn ramp(t0: f64, t1: f64, v1: f64) -> TimeFunction {
    TimeFunction::Ramp {
        t0,
        t1,
        v0: 0.0,
        v1,
    }
}

/// Builds a [`Model`] of dimension `D` step by step; see the module
/// documentation.
#[derive(Debug, Clone)]
pub struct ModelBuilder<const D: usize = 2> {
    /// The model built so far.
    model: Model<D>,
}

impl ModelBuilder<3> {
    /// An empty solid (3D) model.
    pub fn solid() -> Self {
        Self::new(AnalysisKind::Solid)
    }

    /// Adds rigid surface tool `name`.
    pub fn surface(
        mut self,
        name: &str,
        geometry: impl Into<crate::model::SurfaceShape>,
        motion: crate::model::SurfaceMotion,
    ) -> Self {
        self.model.surfaces.push(crate::model::SurfaceTool {
            name: name.into(),
            geometry: geometry.into(),
            motion,
        });
        self
    }

    /// Contact pair `name`: the slave `faces` of `body` against surface
    /// tool `tool`.
    pub fn contact_faces(
        mut self,
        name: &str,
        body: &str,
        faces: Vec<crate::mesh::Facet>,
        tool: &str,
        method: ContactMethod,
    ) -> Self {
        let mut pair = self.pair(name, body, Vec::new());
        let mut nodes: Vec<usize> = faces.iter().flat_map(|f| f.nodes().to_vec()).collect();
        nodes.sort_unstable();
        nodes.dedup();
        pair.nodes = nodes;
        pair.faces = faces;
        pair.master = ContactMaster::Tool(
            self.model
                .surfaces
                .iter()
                .position(|t| t.name == tool)
                .unwrap_or_else(|| panic!("test kit: no surface tool `{tool}`")),
        );
        pair.method = method;
        self.model.contacts.push(pair);
        self
    }
}

impl<const D: usize> ModelBuilder<D> {
    /// An empty model of analysis `kind`, unit thickness.
    pub fn new(kind: AnalysisKind) -> Self {
        ModelBuilder {
            model: Model {
                analysis: Analysis {
                    kind,
                    thickness: 1.0,
                },
                mesh: Mesh::default(),
                bodies: Vec::new(),
                materials: Vec::new(),
                constraints: Vec::new(),
                loads: Vec::new(),
                tools: Vec::new(),
                surfaces: Vec::new(),
                contacts: Vec::new(),
                steps: Vec::new(),
                output: OutputRequest::default(),
                thermal: None,
                initial_velocities: Vec::new(),
                discrete: Vec::new(),
            },
        }
    }

    /// Face set `name` (qualified, `body.set`) of the mesh built so far.
    pub fn face_set(&self, name: &str) -> Vec<crate::mesh::Facet> {
        self.model
            .mesh
            .face_sets
            .get(name)
            .unwrap_or_else(|| panic!("test kit: no face set `{name}`"))
            .clone()
    }

    /// An empty plane-strain model.
    pub fn plane_strain() -> Self {
        Self::new(AnalysisKind::PlaneStrain)
    }

    /// An empty plane-stress model.
    pub fn plane_stress() -> Self {
        Self::new(AnalysisKind::PlaneStress)
    }

    /// An empty axisymmetric model (x = r, y = z).
    pub fn axisymmetric() -> Self {
        Self::new(AnalysisKind::Axisymmetric)
    }

    /// The model built so far (e.g. to read the qualified sets of the
    /// bodies already added).
    pub fn model(&self) -> &Model<D> {
        &self.model
    }

    /// Node set `name` (qualified, `body.set`) of the mesh built so far.
    pub fn node_set(&self, name: &str) -> Vec<usize> {
        self.model
            .mesh
            .node_sets
            .get(name)
            .unwrap_or_else(|| panic!("test kit: no node set `{name}`"))
            .clone()
    }

    /// Edge set `name` (qualified, `body.set`) of the mesh built so far.
    pub fn edge_set(&self, name: &str) -> Vec<[usize; 2]> {
        self.model
            .mesh
            .edge_sets
            .get(name)
            .unwrap_or_else(|| panic!("test kit: no edge set `{name}`"))
            .clone()
    }

    /// Out-of-plane thickness (plane strain and plane stress).
    pub fn thickness(mut self, thickness: f64) -> Self {
        self.model.analysis.thickness = thickness;
        self
    }

    /// Adds material `name` with `law`.
    pub fn material(mut self, name: &str, law: MaterialLaw) -> Self {
        self.model.materials.push(Material {
            name: name.into(),
            law,
            density: 0.0,
        });
        self
    }

    /// Mass density of the last material added.
    pub fn density(mut self, rho: f64) -> Self {
        self.model
            .materials
            .last_mut()
            .expect("test kit: `density` after `material`")
            .density = rho;
        self
    }

    /// Adds the linear elastic material `name`.
    pub fn elastic(self, name: &str, young: f64, poisson: f64) -> Self {
        self.material(name, MaterialLaw::LinearElastic { young, poisson })
    }

    fn material_index(&self, name: &str) -> usize {
        self.model
            .materials
            .iter()
            .position(|m| m.name == name)
            .unwrap_or_else(|| panic!("test kit: no material `{name}` (add it first)"))
    }

    fn body_index(&self, name: &str) -> usize {
        self.model
            .bodies
            .iter()
            .position(|b| b.name == name)
            .unwrap_or_else(|| panic!("test kit: no body `{name}` (add it first)"))
    }

    fn tool_index(&self, name: &str) -> usize {
        self.model
            .tools
            .iter()
            .position(|t| t.name == name)
            .unwrap_or_else(|| panic!("test kit: no tool `{name}` (add it first)"))
    }

    /// Replaces the global mesh by `mesh`, bodies left out (for kernels that
    /// need nodes and cells but no body).
    pub fn mesh(mut self, mesh: Mesh<D>) -> Self {
        self.model.mesh = mesh;
        self
    }

    /// Appends body `name` made of all of `mesh`, of material `material`
    /// (full integration, small strain).
    pub fn body(mut self, name: &str, mesh: Mesh<D>, material: &str) -> Self {
        let material = self.material_index(material);
        let global = &mut self.model.mesh;
        let (n0, c0) = (global.nodes.len(), global.cells.len());
        global.nodes.extend_from_slice(&mesh.nodes);
        global.cells.extend_shifted(&mesh.cells, n0);
        for (k, v) in &mesh.node_sets {
            global
                .node_sets
                .insert(format!("{name}.{k}"), v.iter().map(|n| n + n0).collect());
        }
        for (k, v) in &mesh.edge_sets {
            global.edge_sets.insert(
                format!("{name}.{k}"),
                v.iter().map(|e| [e[0] + n0, e[1] + n0]).collect(),
            );
        }
        for (k, v) in &mesh.face_sets {
            global.face_sets.insert(
                format!("{name}.{k}"),
                v.iter().map(|f| f.shifted(n0)).collect(),
            );
        }
        self.model.bodies.push(Body {
            name: name.into(),
            nodes: n0..global.nodes.len(),
            cells: c0..global.cells.len(),
            material,
            formulation: Formulation::Full,
            kinematics: Kinematics::Small,
        });
        self
    }

    fn last_body(&mut self) -> &mut Body {
        self.model
            .bodies
            .last_mut()
            .expect("test kit: add a body first")
    }

    /// Element formulation of the last body.
    pub fn formulation(mut self, formulation: Formulation) -> Self {
        self.last_body().formulation = formulation;
        self
    }

    /// Kinematics of the last body.
    pub fn kinematics(mut self, kinematics: Kinematics) -> Self {
        self.last_body().kinematics = kinematics;
        self
    }

    /// Adds a prescribed displacement.
    pub fn constraint(mut self, constraint: Dirichlet) -> Self {
        self.model.constraints.push(constraint);
        self
    }

    /// `component` of `nodes` prescribed to `value(t)`.
    pub fn displace(
        self,
        nodes: impl Into<Vec<usize>>,
        component: usize,
        value: TimeFunction,
    ) -> Self {
        let label = format!("displace {component}");
        self.constraint(Dirichlet {
            label,
            nodes: nodes.into(),
            component,
            value,
        })
    }

    /// `component` of `nodes` fixed at 0.
    pub fn fix(self, nodes: impl Into<Vec<usize>>, component: usize) -> Self {
        let label = format!("fix {component}");
        self.constraint(Dirichlet {
            label,
            nodes: nodes.into(),
            component,
            value: TimeFunction::Constant(0.0),
        })
    }

    /// Adds an external load.
    pub fn load(mut self, load: Load) -> Self {
        self.model.loads.push(load);
        self
    }

    /// A force `value(t)` along `component` at each of `nodes`.
    pub fn nodal_force(
        self,
        nodes: impl Into<Vec<usize>>,
        component: usize,
        value: TimeFunction,
    ) -> Self {
        self.load(Load::NodalForce {
            label: format!("force {component}"),
            nodes: nodes.into(),
            component,
            value,
        })
    }

    /// A pressure `value(t)` on boundary `edges` (body on their left).
    pub fn pressure(self, edges: Vec<[usize; 2]>, value: TimeFunction) -> Self {
        self.load(Load::Pressure {
            label: "pressure".into(),
            edges,
            value,
        })
    }

    /// Adds rigid tool `name`.
    pub fn tool(mut self, name: &str, geometry: ToolGeometry, motion: ToolMotion) -> Self {
        self.model.tools.push(RigidTool {
            name: name.into(),
            geometry,
            motion,
            free_rotation: None,
        });
        self
    }

    fn pair(&self, name: &str, body: &str, edges: Vec<[usize; 2]>) -> ContactPair {
        let mut nodes: Vec<usize> = edges.iter().flat_map(|e| [e[0], e[1]]).collect();
        nodes.sort_unstable();
        nodes.dedup();
        ContactPair {
            name: name.into(),
            body: self.body_index(body),
            edges,
            faces: Vec::new(),
            nodes,
            master: ContactMaster::Tool(usize::MAX),
            strategy: ContactStrategy::default(),
            search: LocalSearch::default(),
            formulation: crate::model::ContactFormulation::default(),
            smoothing: crate::model::NormalSmoothing::default(),
            method: ContactMethod::Penalty {
                kind: crate::model::PenaltyKind::Area,
                stiffness: 1.0,
            },
            prof: None,
            friction: None,
            local_penalty: Vec::new(),
        }
    }

    /// Contact pair `name`: the slave `edges` of `body` against tool `tool`.
    pub fn contact_tool(
        mut self,
        name: &str,
        body: &str,
        edges: Vec<[usize; 2]>,
        tool: &str,
        method: ContactMethod,
    ) -> Self {
        let mut pair = self.pair(name, body, edges);
        pair.master = ContactMaster::Tool(self.tool_index(tool));
        pair.method = method;
        self.model.contacts.push(pair);
        self
    }

    /// Node-to-segment pair `name`: the slave `edges` of `body` against the
    /// master edges `master_edges` of `master_body`.
    pub fn contact_surface(
        mut self,
        name: &str,
        (body, edges): (&str, Vec<[usize; 2]>),
        (master_body, master_edges): (&str, Vec<[usize; 2]>),
        method: ContactMethod,
    ) -> Self {
        let mut pair = self.pair(name, body, edges);
        let mut nodes: Vec<usize> = master_edges.iter().flat_map(|e| [e[0], e[1]]).collect();
        nodes.sort_unstable();
        nodes.dedup();
        pair.master = ContactMaster::Surface {
            body: self.body_index(master_body),
            edges: master_edges,
            faces: Vec::new(),
            nodes,
        };
        pair.method = method;
        self.model.contacts.push(pair);
        self
    }

    fn last_pair(&mut self) -> &mut ContactPair {
        self.model
            .contacts
            .last_mut()
            .expect("test kit: add a contact pair first")
    }

    /// Formulation of the last pair (node-to-segment or mortar).
    pub fn formulation_of_pair(mut self, formulation: crate::model::ContactFormulation) -> Self {
        self.last_pair().formulation = formulation;
        self
    }

    /// Master normal smoothing of the last pair.
    pub fn smoothing_of_pair(mut self, smoothing: crate::model::NormalSmoothing) -> Self {
        self.last_pair().smoothing = smoothing;
        self
    }

    /// Coulomb friction of the last pair.
    pub fn friction(mut self, friction: Friction) -> Self {
        self.last_pair().friction = Some(friction);
        self
    }

    /// Search window `prof` of the last pair.
    pub fn prof(mut self, prof: f64) -> Self {
        self.last_pair().prof = Some(prof);
        self
    }

    /// Strategy of the last pair.
    pub fn strategy(mut self, strategy: ContactStrategy) -> Self {
        self.last_pair().strategy = strategy;
        self
    }

    /// Local search test of the last pair.
    pub fn search(mut self, search: LocalSearch) -> Self {
        self.last_pair().search = search;
        self
    }

    /// Appends step `name` from the end of the previous step (or 0) to
    /// `t_end` in `increments` equal increments (minimum increment 1/1024
    /// of the initial one, default Newton settings).
    pub fn step(mut self, name: &str, t_end: f64, increments: usize) -> Self {
        let t_start = self.model.steps.last().map_or(0.0, |s| s.t_end);
        self.model.steps.push(Step {
            name: name.into(),
            t_start,
            t_end,
            increments,
            min_fraction: 1.0 / 1024.0,
            newton: NewtonSettings::default(),
            dynamic: None,
        });
        self
    }

    /// Makes the last step dynamic.
    pub fn dynamic(mut self, dynamic: crate::model::Dynamic) -> Self {
        self.last_step().dynamic = Some(dynamic);
        self
    }

    /// A spring of stiffness `k` and a dashpot `c` from each of `nodes` to
    /// the ground (every component).
    pub fn ground_spring(mut self, nodes: impl Into<Vec<usize>>, k: f64, c: f64) -> Self {
        self.model.discrete.push(crate::model::Discrete::Ground {
            label: "ground spring".into(),
            nodes: nodes.into(),
            stiffness: k,
            damping: c,
        });
        self
    }

    /// A point mass `m` at each of `nodes`.
    pub fn point_mass(mut self, nodes: impl Into<Vec<usize>>, m: f64) -> Self {
        self.model.discrete.push(crate::model::Discrete::Mass {
            label: "point mass".into(),
            nodes: nodes.into(),
            mass: m,
        });
        self
    }

    /// Initial velocity `value` of component `component` on `nodes`.
    pub fn initial_velocity(
        mut self,
        nodes: impl Into<Vec<usize>>,
        component: usize,
        value: f64,
    ) -> Self {
        let nodes = nodes.into();
        self.model
            .initial_velocities
            .push(crate::model::InitialVelocity {
                label: "initial velocity".into(),
                nodes,
                component,
                value,
            });
        self
    }

    fn last_step(&mut self) -> &mut Step {
        self.model
            .steps
            .last_mut()
            .expect("test kit: add a step first")
    }

    /// Newton settings of the last step.
    pub fn newton(mut self, newton: NewtonSettings) -> Self {
        self.last_step().newton = newton;
        self
    }

    /// Residual and displacement tolerances of the last step.
    pub fn tol(mut self, tol: f64) -> Self {
        let s = self.last_step();
        s.newton.tol = tol;
        s.newton.tol_displacement = tol;
        self
    }

    /// Smallest increment of the last step, as a fraction of its initial
    /// increment.
    pub fn min_fraction(mut self, fraction: f64) -> Self {
        self.last_step().min_fraction = fraction;
        self
    }

    /// Output request.
    pub fn output(mut self, output: OutputRequest) -> Self {
        self.model.output = output;
        self
    }

    /// Thermal scene.
    pub fn thermal(mut self, thermal: crate::model::thermal::ThermalScene) -> Self {
        self.model.thermal = Some(thermal);
        self
    }

    /// The model.
    pub fn build(self) -> Model<D> {
        self.model
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Cell;

    #[test]
    fn builder_appends_bodies_with_shifted_numbers_and_qualified_sets() {
        let square = |x0: f64| {
            let mut m = Mesh::new(
                vec![[x0, 0.0], [x0 + 1.0, 0.0], [x0 + 1.0, 1.0], [x0, 1.0]],
                vec![Cell::quad(0, 1, 2, 3)],
            );
            m.node_sets.insert("bottom".into(), vec![0, 1]);
            m.edge_sets.insert("bottom".into(), vec![[0, 1]]);
            m
        };
        let b = ModelBuilder::plane_strain()
            .elastic("m", 1.0, 0.3)
            .body("a", square(0.0), "m")
            .body("b", square(2.0), "m")
            .kinematics(Kinematics::Finite);
        assert_eq!(b.node_set("b.bottom"), vec![4, 5]);
        let edges = b.edge_set("b.bottom");
        let m = b
            .contact_surface(
                "b -> a",
                ("b", edges),
                ("a", vec![[2, 3]]),
                ContactMethod::Lagrange {
                    formulation: crate::model::LagrangeFormulation::Single,
                },
            )
            .step("one", 1.0, 1)
            .step("two", 3.0, 2)
            .tol(1e-11)
            .build();
        assert_eq!(m.bodies[1].nodes, 4..8);
        assert_eq!(m.bodies[1].cells, 1..2);
        assert_eq!(m.bodies[1].kinematics, Kinematics::Finite);
        assert_eq!(m.bodies[0].kinematics, Kinematics::Small);
        assert_eq!(m.mesh.cells.nodes(1), &[4, 5, 6, 7]);
        assert_eq!(m.contacts[0].nodes, vec![4, 5]);
        assert_eq!(m.contacts[0].body, 1);
        assert!(matches!(
            m.contacts[0].master,
            ContactMaster::Surface { body: 0, .. }
        ));
        assert_eq!((m.steps[1].t_start, m.steps[1].t_end), (1.0, 3.0));
        assert_eq!(m.steps[1].newton.tol, 1e-11);
        assert_eq!(m.steps[0].newton.tol, NewtonSettings::default().tol);
    }
}
