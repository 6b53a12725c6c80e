//! A penalty written relative to the mesh and the material
//! (`stiffness = 10 * E / h`, issue "A deck language .. for daily work"):
//! the coefficient is evaluated per slave node with `E` the slave body's
//! Young's modulus and `h` the mean length of the slave facet edges at the
//! node. Checked against the same quantity computed here from the lowered
//! mesh, on a graded half disc (2D) and a graded brick (3D), and for the
//! augmented Lagrangian; bad expressions are diagnosed at their span.

use ctc_engine::model::{AnyModel, ContactMethod};
use ctc_lang::{check, compile_any, Source};
use std::collections::BTreeMap;

/// The Hertz deck of `examples/` with the penalty written as `coef`.
fn hertz(coef: &str) -> String {
    format!(
        "analysis {{ dimension = plane_strain  thickness = 1 }}\n\
         material soft {{ elastic {{ E = 200  nu = 0.3 }} }}\n\
         body disc {{\n  mesh = half_disc {{ center = (0, 8)  radius = 8  radial = 6  circumferential = 16\n\
         radial_grading = geometric(0.15)  circumferential_grading = center(8)  upper = false  element = quad4 }}\n\
         material = soft\n}}\n\
         tool floor = plane {{ point = (0, 0)  normal = (0, 1) }}\n\
         contact disc.arc -> floor {{ method = {coef} }}\n\
         fix disc.flat {{ ux }}\n\
         displace disc.flat {{ uy = ramp(0, -0.08) }}\n\
         step press {{ time = 0 .. 1  increments = 4 }}\n"
    )
}

/// Mean adjacent edge length per node of a list of 2D edges.
fn mean_edge(x: &[[f64; 2]], edges: &[[usize; 2]]) -> BTreeMap<usize, f64> {
    let mut s: BTreeMap<usize, (f64, f64)> = BTreeMap::new();
    for &[a, b] in edges {
        let l = ((x[a][0] - x[b][0]).powi(2) + (x[a][1] - x[b][1]).powi(2)).sqrt();
        for n in [a, b] {
            let e = s.entry(n).or_default();
            e.0 += l;
            e.1 += 1.0;
        }
    }
    s.into_iter().map(|(n, (t, c))| (n, t / c)).collect()
}

#[test]
fn penalty_10_e_over_h_is_evaluated_per_slave_node_in_2d() {
    let src = Source::new("rel.ctc", hertz("penalty { stiffness = 10 * E / h }"));
    let Ok(AnyModel::D2(m)) = compile_any(&src) else {
        panic!("{}", check(&src).diagnostics.render(&src));
    };
    let cp = &m.contacts[0];
    let h = mean_edge(&m.mesh.nodes, &cp.edges);
    assert_eq!(cp.local_penalty.len(), cp.nodes.len());
    assert_eq!(h.len(), cp.nodes.len());
    let mut worst = 0.0f64;
    for &(node, k) in &cp.local_penalty {
        let expected = 10.0 * 200.0 / h[&node];
        worst = worst.max((k / expected - 1.0).abs());
        assert_eq!(cp.method_at(node), {
            let ContactMethod::Penalty { kind, .. } = cp.method.clone() else {
                panic!()
            };
            ContactMethod::Penalty { kind, stiffness: k }
        });
    }
    assert!(worst < 1e-14, "relative error {worst:e}");
    // graded mesh: the coefficient varies along the arc
    let ks: Vec<f64> = cp.local_penalty.iter().map(|e| e.1).collect();
    let (lo, hi) = (
        ks.iter().cloned().fold(f64::INFINITY, f64::min),
        ks.iter().cloned().fold(0.0, f64::max),
    );
    assert!(hi > 2.0 * lo, "{lo} .. {hi}");
    // the pair's method carries the stiffest value; nodes outside the list
    // (none here) would get it too
    assert_eq!(
        cp.method,
        ContactMethod::Penalty {
            kind: ctc_engine::model::PenaltyKind::Area,
            stiffness: hi
        }
    );
    // the plan says it is per node
    let plan = ctc_lang::explain(&m);
    assert!(
        plan.contains("relative to E and the local element size h"),
        "{plan}"
    );
}

#[test]
fn augmented_lagrange_penalty_can_be_relative_and_uses_parameters() {
    let src = Source::new(
        "rel.ctc",
        format!(
            "let c = 5\n{}",
            hertz("augmented_lagrange { penalty = c * E / h  tolerance = 1e-6 }")
        ),
    );
    let Ok(AnyModel::D2(m)) = compile_any(&src) else {
        panic!("{}", check(&src).diagnostics.render(&src));
    };
    let cp = &m.contacts[0];
    let h = mean_edge(&m.mesh.nodes, &cp.edges);
    for &(node, k) in &cp.local_penalty {
        assert!((k / (5.0 * 200.0 / h[&node]) - 1.0).abs() < 1e-14);
        assert!(
            matches!(cp.method_at(node), ContactMethod::AugmentedLagrange { penalty, .. } if penalty == k)
        );
    }
    assert_eq!(cp.local_penalty.len(), cp.nodes.len());
}

#[test]
fn an_absolute_penalty_has_no_local_values() {
    let src = Source::new("abs.ctc", hertz("penalty { stiffness = 2e4 }"));
    let Ok(AnyModel::D2(m)) = compile_any(&src) else {
        panic!("{}", check(&src).diagnostics.render(&src));
    };
    assert!(m.contacts[0].local_penalty.is_empty());
}

#[test]
fn penalty_relative_in_3d_uses_the_face_edges() {
    let src = Source::new(
        "rel3.ctc",
        "analysis { dimension = 3d }\n\
         material m { elastic { E = 1000  nu = 0.3 } }\n\
         body b {\n  mesh = box { size = (1, 1, 0.5)  divisions = (4, 2, 2) }\n  material = m\n}\n\
         tool floor = plane { point = (0, 0, 0)  normal = (0, 0, 1) }\n\
         contact b.zmin -> floor { method = penalty { stiffness = 10 * E / h } }\n\
         fix b.zmax { ux uy uz }\n\
         step s { time = 0 .. 1  increments = 1 }\n",
    );
    let m = match compile_any(&src) {
        Ok(AnyModel::D3(m)) => m,
        Ok(_) => panic!("not 3d"),
        Err(d) => panic!("{}", d.render(&src)),
    };
    let cp = &m.contacts[0];
    // bottom face 1 x 1 in 4 x 2 quads of 0.25 x 0.5: a corner node meets
    // one edge of each length (mean 0.375), an edge-midside node on the
    // long side (y = 0) meets two 0.25 edges and one 0.5 edge, ..
    let x = &m.mesh.nodes;
    let mut s: BTreeMap<usize, (f64, f64)> = BTreeMap::new();
    for f in &cp.faces {
        let n = f.nodes();
        for k in 0..n.len() {
            let (a, b) = (n[k], n[(k + 1) % n.len()]);
            let l: f64 = (0..3)
                .map(|c| (x[a][c] - x[b][c]).powi(2))
                .sum::<f64>()
                .sqrt();
            for q in [a, b] {
                let e = s.entry(q).or_default();
                e.0 += l;
                e.1 += 1.0;
            }
        }
    }
    assert_eq!(cp.local_penalty.len(), 15);
    for &(node, k) in &cp.local_penalty {
        let (t, c) = s[&node];
        assert!((k / (10.0 * 1000.0 * c / t) - 1.0).abs() < 1e-14);
    }
    let corner = cp
        .local_penalty
        .iter()
        .find(|(n, _)| x[*n][0] == 0.0 && x[*n][1] == 0.0)
        .unwrap();
    assert!(
        (corner.1 - 10.0 * 1000.0 / 0.375).abs() < 1e-9,
        "{}",
        corner.1
    );
}

#[test]
fn a_relative_penalty_that_is_not_positive_is_diagnosed_at_its_expression() {
    let src = Source::new("neg.ctc", hertz("penalty { stiffness = 10 * E / h - 1e6 }"));
    let text = compile_any(&src).unwrap_err().render(&src);
    assert!(
        text.contains("the penalty coefficient must be a positive number"),
        "{text}"
    );
    assert!(text.contains("10 * E / h - 1e6"), "{text}");
}

#[test]
fn an_unknown_name_in_a_relative_penalty_is_diagnosed() {
    let src = Source::new("bad.ctc", hertz("penalty { stiffness = 10 * E / hh }"));
    let text = compile_any(&src).unwrap_err().render(&src);
    assert!(text.contains("hh"), "{text}");
}

#[test]
fn a_parameter_named_e_is_shadowed_with_a_warning() {
    let src = Source::new(
        "shadow.ctc",
        format!("let E = 7\n{}", hertz("penalty { stiffness = 10 * E / h }")),
    );
    let c = check(&src);
    let text = c.diagnostics.render(&src);
    assert!(c.model.is_some(), "{text}");
    assert!(
        text.contains("`E` is the slave body's Young's modulus"),
        "{text}"
    );
    let Ok(AnyModel::D2(m)) = compile_any(&src) else {
        panic!()
    };
    let h = mean_edge(&m.mesh.nodes, &m.contacts[0].edges);
    let (node, k) = m.contacts[0].local_penalty[0];
    assert!((k / (10.0 * 200.0 / h[&node]) - 1.0).abs() < 1e-14);
}
