//! A BREP tool: faces, their coedges, vertices and adjacency; the closest
//! point of the whole tool (see the module doc of [`crate::brep`]).

use super::edge::{eval as edge_eval, Coedge, EdgeFoot};
use super::face::Face;
use super::search::{Counters, SearchState};
use crate::nurbs::{ProjectOptions, SurfaceFoot};
use crate::trim::Containment;
use crate::{offset, Aabb, FootKind, Mat3, Projection, ProjectionError, Vec2, Vec3};

/// Tolerances and settings of a BREP tool.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct BrepOptions {
    /// Points closer than this (3D) are the same point: shared edges,
    /// vertices, degenerate (zero-length) edges. `None`: `1e-7` of the
    /// tool's size.
    pub merge_tolerance: Option<f64>,
    /// A foot outside its face by less than this (3D) is still on the face.
    /// `None`: 10 times the merge tolerance.
    pub seam_tolerance: Option<f64>,
    /// Surface projection settings.
    pub projection: ProjectOptions,
}

/// A vertex: where edges of the tool end.
#[derive(Debug, Clone, PartialEq)]
pub struct Vertex {
    /// Position.
    pub point: Vec3,
    /// Angle-weighted pseudonormal (unit) of the faces meeting there.
    pub pseudonormal: Vec3,
    /// Whether a free (unshared) edge ends here.
    pub free: bool,
}

/// A tool made of faces.
#[derive(Debug, Clone, PartialEq)]
pub struct BrepTool {
    /// Faces.
    pub faces: Vec<Face>,
    /// Every face's boundary curves.
    pub coedges: Vec<Coedge>,
    /// Coedges of each face.
    pub face_coedges: Vec<Vec<usize>>,
    /// Faces sharing an edge or a vertex with each face.
    pub neighbours: Vec<Vec<usize>>,
    /// Vertices.
    pub vertices: Vec<Vertex>,
    /// Tolerances (resolved).
    pub merge_tolerance: f64,
    /// Seam tolerance (resolved).
    pub seam_tolerance: f64,
    /// Surface projection settings.
    pub projection: ProjectOptions,
    /// Box of the whole tool.
    pub bbox: Aabb,
}

/// No vertex at this coedge end (a joint with a seam or a pole).
const NO_VERTEX: usize = usize::MAX;

/// The best candidate so far.
#[derive(Debug, Clone, Copy)]
enum Candidate {
    /// Face `face`, foot `foot`.
    Interior { face: usize, foot: SurfaceFoot },
    /// Coedge `coedge`, foot `foot`.
    Edge { coedge: usize, foot: EdgeFoot },
}

impl Candidate {
    fn distance(&self) -> f64 {
        match self {
            Candidate::Interior { foot, .. } => foot.distance,
            Candidate::Edge { foot, .. } => foot.distance,
        }
    }

    fn rank(&self) -> u8 {
        match self {
            Candidate::Interior { .. } => 0,
            Candidate::Edge { foot, .. } => 1 + u8::from(foot.end.is_some()),
        }
    }
}

impl BrepTool {
    /// Builds the tool: coedges, shared edges (partners), seams, poles,
    /// vertices and pseudonormals, adjacency.
    pub fn new(faces: Vec<Face>, options: BrepOptions) -> Result<Self, String> {
        if faces.is_empty() {
            return Err("BREP tool: no face".into());
        }
        let bbox = faces.iter().fold(Aabb::empty(), |b, f| b.union(&f.bbox));
        let size = bbox.diagonal();
        let merge = options.merge_tolerance.unwrap_or(1e-7 * size);
        let seam = options.seam_tolerance.unwrap_or(10.0 * merge);
        let mut coedges = Vec::new();
        let mut face_coedges = Vec::new();
        let mut joints = Vec::new(); // (incoming coedge, outgoing coedge)
        for (fi, f) in faces.iter().enumerate() {
            let mut list = Vec::new();
            for lp in f.loops() {
                let first = coedges.len();
                for c in &lp.curves {
                    let mut ce = Coedge::new(fi, &f.surface, c.clone());
                    ce.degenerate = ce.length <= merge;
                    ce.vertices = [NO_VERTEX, NO_VERTEX];
                    list.push(coedges.len());
                    coedges.push(ce);
                }
                let n = coedges.len() - first;
                for k in 0..n {
                    joints.push((first + k, first + (k + 1) % n));
                }
            }
            face_coedges.push(list);
        }
        // Partners: coedges along the same 3D curve.
        let n = coedges.len();
        for i in 0..n {
            if coedges[i].degenerate || coedges[i].partner.is_some() {
                continue;
            }
            for j in i + 1..n {
                if coedges[j].degenerate || coedges[j].partner.is_some() {
                    continue;
                }
                if coedges[i].bbox.distance(&coedges[j].bbox.min)
                    > coedges[j].bbox.diagonal() + merge
                {
                    continue;
                }
                if same_curve(&faces, &coedges[i], &coedges[j], merge) {
                    coedges[i].partner = Some(j);
                    coedges[j].partner = Some(i);
                    if coedges[i].face == coedges[j].face {
                        coedges[i].seam = true;
                        coedges[j].seam = true;
                    }
                    break;
                }
            }
        }
        // Vertices at joints of two edges.
        let mut vertices: Vec<Vertex> = Vec::new();
        let mut weighted: Vec<Vec3> = Vec::new();
        for &(a, b) in &joints {
            if !(coedges[a].is_edge() && coedges[b].is_edge()) {
                continue;
            }
            let fa = &faces[coedges[a].face];
            let [_, ta] = coedges[a].curve.domain();
            let [tb, _] = coedges[b].curve.domain();
            let ea = edge_eval(&fa.surface, &coedges[a].curve, ta);
            let eb = edge_eval(&fa.surface, &coedges[b].curve, tb);
            let p = ea.p;
            let angle = {
                let (u, w) = (-ea.d1, eb.d1);
                let (nu, nw) = (u.norm(), w.norm());
                if nu > 0.0 && nw > 0.0 {
                    (u.dot(&w) / (nu * nw)).clamp(-1.0, 1.0).acos()
                } else {
                    0.0
                }
            };
            let normal = fa.normal(coedges[a].curve.eval(ta).p);
            let free = coedges[a].partner.is_none() || coedges[b].partner.is_none();
            let v = match vertices.iter().position(|v| (v.point - p).norm() <= merge) {
                Some(v) => v,
                None => {
                    vertices.push(Vertex {
                        point: p,
                        pseudonormal: Vec3::zeros(),
                        free: false,
                    });
                    weighted.push(Vec3::zeros());
                    vertices.len() - 1
                }
            };
            weighted[v] += normal * angle;
            vertices[v].free |= free;
            coedges[a].vertices[1] = v;
            coedges[b].vertices[0] = v;
        }
        for (v, w) in vertices.iter_mut().zip(&weighted) {
            v.pseudonormal = w.try_normalize(0.0).unwrap_or_else(Vec3::z);
        }
        // Adjacency.
        let mut neighbours = vec![Vec::new(); faces.len()];
        let link = |a: usize, b: usize, nb: &mut Vec<Vec<usize>>| {
            if a != b && !nb[a].contains(&b) {
                nb[a].push(b);
                nb[b].push(a);
            }
        };
        for c in &coedges {
            if let Some(p) = c.partner {
                link(c.face, coedges[p].face, &mut neighbours);
            }
        }
        for v in 0..vertices.len() {
            let fs: Vec<usize> = coedges
                .iter()
                .filter(|c| c.vertices.contains(&v))
                .map(|c| c.face)
                .collect();
            for &a in &fs {
                for &b in &fs {
                    link(a, b, &mut neighbours);
                }
            }
        }
        for nb in &mut neighbours {
            nb.sort_unstable();
        }
        Ok(BrepTool {
            faces,
            coedges,
            face_coedges,
            neighbours,
            vertices,
            merge_tolerance: merge,
            seam_tolerance: seam,
            projection: options.projection,
            bbox,
        })
    }

    /// Makes the face orientations consistent across shared edges, starting
    /// from face `seed` with orientation `orientation` (`+1`: `S_u x S_v`
    /// into free space). Errors when the faces cannot be oriented
    /// consistently (a Moebius-like arrangement).
    pub fn orient(&mut self, seed: usize, orientation: f64) -> Result<(), String> {
        let nf = self.faces.len();
        let mut set = vec![false; nf];
        let mut queue = std::collections::VecDeque::new();
        for start in std::iter::once(seed).chain(0..nf) {
            if set[start] {
                continue;
            }
            if start == seed {
                self.faces[seed].orientation = if orientation < 0.0 { -1.0 } else { 1.0 };
            }
            set[start] = true;
            queue.push_back(start);
            while let Some(f) = queue.pop_front() {
                for &ci in &self.face_coedges[f].clone() {
                    let c = &self.coedges[ci];
                    let Some(pi) = c.partner else { continue };
                    if c.seam {
                        continue;
                    }
                    let g = self.coedges[pi].face;
                    let (da, db) = (self.walk(ci), self.walk(pi));
                    let consistent = da.dot(&db) < 0.0;
                    if !set[g] {
                        if !consistent {
                            self.faces[g].orientation *= -1.0;
                        }
                        set[g] = true;
                        queue.push_back(g);
                    } else if !consistent {
                        return Err(format!(
                            "BREP tool: faces {} and {} cannot be oriented consistently",
                            f + 1,
                            g + 1
                        ));
                    }
                }
            }
        }
        // Pseudonormals follow the orientations.
        let faces = &self.faces;
        let coedges = &self.coedges;
        for (vi, v) in self.vertices.iter_mut().enumerate() {
            let mut w = Vec3::zeros();
            for c in coedges.iter().filter(|c| c.vertices[1] == vi) {
                let f = &faces[c.face];
                let [_, t] = c.curve.domain();
                let next = coedges
                    .iter()
                    .find(|d| d.face == c.face && d.vertices[0] == vi);
                let e = edge_eval(&f.surface, &c.curve, t);
                let angle = next.map_or(0.0, |d| {
                    let eb = edge_eval(&f.surface, &d.curve, d.curve.domain()[0]);
                    let (u, s) = (-e.d1, eb.d1);
                    (u.dot(&s) / (u.norm() * s.norm()).max(f64::MIN_POSITIVE))
                        .clamp(-1.0, 1.0)
                        .acos()
                });
                w += f.normal(c.curve.eval(t).p) * angle;
            }
            v.pseudonormal = w.try_normalize(0.0).unwrap_or(v.pseudonormal);
        }
        Ok(())
    }

    /// Walking direction of a coedge at its middle, with its face on the
    /// left seen from the face's oriented normal.
    fn walk(&self, ci: usize) -> Vec3 {
        let c = &self.coedges[ci];
        let f = &self.faces[c.face];
        let [a, b] = c.curve.domain();
        let tm = 0.5 * (a + b);
        let e = edge_eval(&f.surface, &c.curve, tm);
        // In the parameter plane the face is on the left of a curve when the
        // face point just left of it is inside.
        let cd = c.curve.eval(tm);
        let left = Vec2::new(-cd.d1.y, cd.d1.x).normalize();
        let probe = cd.p
            + left
                * (1e-6
                    * (f.surface.domain()[0][1] - f.surface.domain()[0][0])
                        .abs()
                        .max(1e-300));
        let sense = if f.contains(probe).0.is_in() {
            1.0
        } else {
            -1.0
        };
        e.d1 * (sense * f.orientation)
    }

    /// Closest point of the tool to `x` (reference frame), see the module
    /// doc. `state` carries the last face and parameter (updated), and the
    /// search distance; `counters` accumulates the work.
    pub fn project(
        &self,
        x: &Vec3,
        state: &mut SearchState,
        counters: &mut Counters,
    ) -> Result<Projection, ProjectionError> {
        counters.queries += 1;
        let nf = self.faces.len();
        let mut order: Vec<usize> = Vec::with_capacity(nf);
        let mut queued = vec![false; nf];
        if let Some(f) = state.last_face.filter(|&f| f < nf) {
            order.push(f);
            queued[f] = true;
            for &g in &self.neighbours[f] {
                order.push(g);
                queued[g] = true;
            }
        }
        order.extend((0..nf).filter(|&f| !queued[f]));
        let mut best: Option<Candidate> = None;
        let mut failure: Option<(usize, ProjectionError)> = None;
        let scale = self.bbox.diagonal().max(f64::MIN_POSITIVE);
        let better = |c: &Candidate, best: &Option<Candidate>| -> bool {
            match best {
                None => true,
                Some(b) => {
                    let (dc, db) = (c.distance(), b.distance());
                    dc < db - 1e-12 * scale || (dc <= db + 1e-12 * scale && c.rank() < b.rank())
                }
            }
        };
        for &f in &order {
            let face = &self.faces[f];
            let bound = face.bbox.distance(x);
            let limit = best
                .map_or(f64::INFINITY, |b| b.distance())
                .min(state.reach);
            if bound > limit {
                counters.faces_skipped += 1;
                continue;
            }
            counters.faces_tested += 1;
            counters.surface_projections += 1;
            let hint = if state.last_face == Some(f) {
                state.last_uv
            } else {
                None
            };
            match face.project_surface(x, hint, &self.projection) {
                Ok(foot) => {
                    counters.newton_iterations += u64::from(foot.iterations);
                    if !foot.on_bound {
                        let (c, rays) = face.contains(foot.uv);
                        counters.parity_rays += rays as u64;
                        let accept = c.is_in() || self.near_boundary(f, &foot.derivs.p, counters);
                        if accept {
                            let cand = Candidate::Interior { face: f, foot };
                            if better(&cand, &best) {
                                best = Some(cand);
                            }
                            continue;
                        }
                    }
                }
                Err(e) => {
                    counters.not_converged += 1;
                    if let ProjectionError::NotConverged { iterations, .. } = e {
                        counters.newton_iterations += u64::from(iterations);
                    }
                    failure = Some((f, e));
                }
            }
            for &ci in &self.face_coedges[f] {
                let c = &self.coedges[ci];
                if !c.is_edge() {
                    continue;
                }
                let limit = best
                    .map_or(f64::INFINITY, |b| b.distance())
                    .min(state.reach);
                if c.bbox.distance(x) > limit {
                    continue;
                }
                counters.edge_projections += 1;
                let foot = self.project_edge(ci, x);
                counters.newton_iterations += u64::from(foot.iterations);
                let cand = Candidate::Edge { coedge: ci, foot };
                if better(&cand, &best) {
                    best = Some(cand);
                }
            }
        }
        // A face that could hold a closer point did not converge: report it.
        if let Some((f, e)) = failure {
            let d = best.map_or(f64::INFINITY, |b| b.distance());
            if self.faces[f].bbox.distance(x) < d {
                return Err(e);
            }
        }
        let Some(best) = best else {
            return Err(ProjectionError::OutOfReach);
        };
        match best {
            Candidate::Interior { face, foot } => {
                state.last_face = Some(face);
                state.last_uv = Some(foot.uv);
                self.faces[face].interior(x, &foot, face)
            }
            Candidate::Edge { coedge, foot } => {
                let c = &self.coedges[coedge];
                state.last_face = Some(c.face);
                state.last_uv = Some(c.curve.eval(foot.t).p);
                Ok(self.edge_projection(coedge, x, &foot))
            }
        }
    }

    /// Whether the surface point `p` of face `f` is within the seam
    /// tolerance of the face's edges.
    fn near_boundary(&self, f: usize, p: &Vec3, counters: &mut Counters) -> bool {
        self.face_coedges[f].iter().any(|&ci| {
            let c = &self.coedges[ci];
            if !c.is_edge() || c.bbox.distance(p) > self.seam_tolerance {
                return false;
            }
            counters.edge_projections += 1;
            self.project_edge(ci, p).distance <= self.seam_tolerance
        })
    }

    /// Closest point of a coedge; a coedge closed in 3D (a full circle
    /// crossing a seam) is retried from its other end when clamped.
    pub fn project_edge(&self, ci: usize, x: &Vec3) -> EdgeFoot {
        let c = &self.coedges[ci];
        let s = &self.faces[c.face].surface;
        let foot = c.project(s, x);
        let closed = c.vertices[0] == NO_VERTEX && c.vertices[1] == NO_VERTEX && {
            let (a, b) = (c.samples[0].1, c.samples[c.samples.len() - 1].1);
            (a - b).norm() <= self.merge_tolerance
        };
        if foot.end.is_some() && closed {
            // Start Newton from the other end: rebuild a coedge view whose
            // nearest sample is that end.
            let other = if foot.end == Some(0) {
                c.samples.len() - 1
            } else {
                0
            };
            let mut view = c.clone();
            view.samples = vec![c.samples[other]];
            let f2 = view.project(s, x);
            if f2.distance < foot.distance || f2.end.is_none() {
                return f2;
            }
        }
        foot
    }

    /// The projection of an edge (or vertex) foot: radius-0 cylinder or
    /// sphere, signed by the pseudonormal.
    fn edge_projection(&self, ci: usize, x: &Vec3, foot: &EdgeFoot) -> Projection {
        let c = &self.coedges[ci];
        let face = &self.faces[c.face];
        let p = foot.derivs.p;
        let d = x - p;
        let dist = d.norm();
        let vertex = foot.end.map(|e| c.vertices[e]).filter(|&v| v != NO_VERTEX);
        let (pseudo, free) = match vertex {
            Some(v) => (self.vertices[v].pseudonormal, self.vertices[v].free),
            None => {
                let n = face.normal(c.curve.eval(foot.t).p);
                match c.partner {
                    Some(pi) => {
                        let pc = &self.coedges[pi];
                        let pf = &self.faces[pc.face];
                        let pfoot = self.project_edge(pi, &p);
                        (n + pf.normal(pc.curve.eval(pfoot.t).p), false)
                    }
                    None => (n, true),
                }
            }
        };
        let s = if free || d.dot(&pseudo) >= 0.0 {
            1.0
        } else {
            -1.0
        };
        let (normal, curvature) = if dist == 0.0 {
            (
                pseudo.try_normalize(0.0).unwrap_or_else(Vec3::z),
                Mat3::zeros(),
            )
        } else if foot.end.is_some() {
            (
                d * (s / dist),
                offset::point(*x, p, s).unwrap_or_else(Mat3::zeros),
            )
        } else {
            (
                d * (s / dist),
                offset::curve(*x, p, foot.derivs.d1, foot.derivs.d2, s).unwrap_or_else(Mat3::zeros),
            )
        };
        let (kind, entity, param) = match vertex {
            Some(v) => (FootKind::Vertex, v, Vec2::zeros()),
            None if foot.end.is_some() => (FootKind::Vertex, ci, Vec2::new(foot.t, 0.0)),
            None => (FootKind::Edge, ci, Vec2::new(foot.t, 0.0)),
        };
        Projection {
            point: p,
            gap: s * dist,
            normal,
            curvature,
            kind,
            param,
            entity,
            iterations: foot.iterations,
            residual: 0.0,
        }
    }

    /// Whether the parameter `uv` of face `f` is on the face.
    pub fn contains(&self, f: usize, uv: Vec2) -> Containment {
        self.faces[f].contains(uv).0
    }
}

/// Whether two coedges run along the same 3D curve (either direction).
fn same_curve(faces: &[Face], a: &Coedge, b: &Coedge, tol: f64) -> bool {
    let sa = &faces[a.face].surface;
    let sb = &faces[b.face].surface;
    let (a0, a1) = (a.samples[0].1, a.samples[a.samples.len() - 1].1);
    let (b0, b1) = (b.samples[0].1, b.samples[b.samples.len() - 1].1);
    let ends = ((a0 - b0).norm() <= tol && (a1 - b1).norm() <= tol)
        || ((a0 - b1).norm() <= tol && (a1 - b0).norm() <= tol);
    if !ends || (a.length - b.length).abs() > 1e-3 * a.length.max(b.length) + tol {
        return false;
    }
    // Interior samples of each lie on the other.
    let k = a.samples.len();
    [k / 4, k / 2, (3 * k) / 4]
        .iter()
        .all(|&i| b.project(sb, &a.samples[i].1).distance <= 10.0 * tol)
        && {
            let m = b.samples.len();
            [m / 3, (2 * m) / 3]
                .iter()
                .all(|&i| a.project(sa, &b.samples[i].1).distance <= 10.0 * tol)
        }
}
