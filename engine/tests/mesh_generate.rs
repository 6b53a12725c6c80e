//! Built-in generators: exact areas, orientation, named sets, grading ratios,
//! element quality, input errors.

/// Under `mesh::` so that `cargo test -p ctc-engine mesh` selects them.
mod mesh {

    use ctc_engine::mesh::generate::{generate, Grading, MeshSpec};
    use ctc_engine::mesh::quality::{cell_area, cell_quality, summary};
    use ctc_engine::mesh::validate::check;
    use ctc_engine::mesh::{CellKind, Mesh};
    use std::collections::BTreeSet;
    use std::f64::consts::PI;

    /// Asserts the invariants every generated mesh must satisfy and returns its
    /// total area: `check` passes, every cell counter-clockwise, the boundary
    /// (from the cells) is exactly the union of the named edge sets, each edge
    /// set is walked head to tail, and each node set of an edge set holds its
    /// sorted nodes.
    fn invariants(mesh: &Mesh, edge_sets: &[&str]) -> f64 {
        if let Err(e) = check(mesh) {
            panic!("check failed: {e:?}");
        }
        let mut area = 0.0;
        for c in &mesh.cells {
            let a = cell_area(mesh, c);
            assert!(a > 0.0, "cell {c:?} area {a}");
            area += a;
        }
        let boundary: BTreeSet<[usize; 2]> = mesh
            .boundary_edges(0..mesh.cells.len())
            .into_iter()
            .collect();
        let mut union = BTreeSet::new();
        let mut total = 0;
        for name in edge_sets {
            let set = mesh
                .edge_sets
                .get(*name)
                .unwrap_or_else(|| panic!("edge set {name} missing"));
            assert!(!set.is_empty(), "edge set {name} empty");
            for w in set.windows(2) {
                assert_eq!(w[0][1], w[1][0], "{name} is not a walk");
            }
            total += set.len();
            union.extend(set.iter().copied());
            let mut nodes: Vec<usize> = set.iter().flatten().copied().collect();
            nodes.sort_unstable();
            nodes.dedup();
            assert_eq!(mesh.node_sets[*name], nodes, "node set {name}");
        }
        assert_eq!(total, union.len(), "edge sets overlap");
        assert_eq!(boundary, union, "boundary != union of the edge sets");
        assert_eq!(
            mesh.edge_sets.len(),
            edge_sets.len(),
            "unexpected edge sets {:?}",
            mesh.edge_sets.keys().collect::<Vec<_>>()
        );
        area
    }

    /// Division lengths along an edge set walk.
    fn lengths(mesh: &Mesh, set: &str) -> Vec<f64> {
        mesh.edge_sets[set]
            .iter()
            .map(|e| {
                let (p, q) = (mesh.nodes[e[0]], mesh.nodes[e[1]]);
                (q[0] - p[0]).hypot(q[1] - p[1])
            })
            .collect()
    }

    /// Angular widths (radians) of the arc divisions, in walking order.
    fn arc_widths(mesh: &Mesh, set: &str, center: [f64; 2]) -> Vec<f64> {
        let ang = |p: [f64; 2]| (p[1] - center[1]).atan2(p[0] - center[0]);
        mesh.edge_sets[set]
            .iter()
            .map(|e| {
                let d = ang(mesh.nodes[e[1]]) - ang(mesh.nodes[e[0]]);
                d.rem_euclid(2.0 * PI)
            })
            .collect()
    }

    /// Area of the polygon inscribed in a circle of radius `r`, sector by sector.
    fn inscribed(r: f64, widths: &[f64]) -> f64 {
        widths.iter().map(|w| 0.5 * r * r * w.sin()).sum()
    }

    fn half_disc(
        radial: usize,
        circumferential: usize,
        rg: Grading,
        cg: Grading,
        upper: bool,
        kind: CellKind,
    ) -> MeshSpec {
        MeshSpec::HalfDisc {
            center: [0.5, 1.0],
            radius: 1.0,
            radial,
            circumferential,
            radial_grading: rg,
            circumferential_grading: cg,
            upper,
            kind,
        }
    }

    #[test]
    fn rectangle_graded_quad4_exact_area_sets_and_ratios() {
        let m = generate(&MeshSpec::Rectangle {
            origin: [-4.0, -4.0],
            size: [8.0, 4.0],
            divisions: [40, 20],
            grading: [
                Grading::Center { ratio: 4.0 },
                Grading::Geometric { ratio: 0.2 },
            ],
            kind: CellKind::Quad4,
        })
        .unwrap();
        let area = invariants(&m, &["bottom", "right", "top", "left"]);
        println!(
            "rectangle 40x20 quad4: area {area} (exact 32), error {:e}",
            area - 32.0
        );
        assert!((area - 32.0).abs() < 1e-12);
        assert_eq!(m.cells.len(), 800);
        assert_eq!(m.nodes.len(), 41 * 21);
        // x grading: end / middle = 4, symmetric
        let b = lengths(&m, "bottom");
        let measured = b[0] / b[19];
        println!("rectangle center(4): measured end/middle {measured}");
        assert!((measured - 4.0).abs() < 1e-9);
        assert!((b[0] - b[39]).abs() < 1e-12);
        // y grading: last (top) / first (bottom) = 0.2; `right` walks upwards
        let r = lengths(&m, "right");
        let measured = r[19] / r[0];
        println!("rectangle geometric(0.2): measured last/first {measured}");
        assert!((measured - 0.2).abs() < 1e-9);
        for (name, p) in [
            ("corner_bl", [-4.0, -4.0]),
            ("corner_br", [4.0, -4.0]),
            ("corner_tr", [4.0, 0.0]),
            ("corner_tl", [-4.0, 0.0]),
        ] {
            assert_eq!(m.nodes[m.node_sets[name][0]], p, "{name}");
        }
        assert!(m.node_sets["top"].iter().all(|&n| m.nodes[n][1] == 0.0));
    }

    #[test]
    fn rectangle_tri3_twice_the_cells_same_area() {
        let m = generate(&MeshSpec::Rectangle {
            origin: [1.0, 2.0],
            size: [3.0, 0.5],
            divisions: [7, 3],
            grading: [Grading::Geometric { ratio: 3.0 }, Grading::Uniform],
            kind: CellKind::Tri3,
        })
        .unwrap();
        let area = invariants(&m, &["bottom", "right", "top", "left"]);
        assert_eq!(m.cells.len(), 42);
        assert!((area - 1.5).abs() < 1e-14);
        assert!(m.cells.iter().all(|c| c.kind == CellKind::Tri3));
    }

    #[test]
    fn half_disc_uniform_area_converges_to_half_circle() {
        let mut errors = Vec::new();
        for k in 0..4 {
            let (radial, circ) = (4 << k, 16 << k);
            for kind in [CellKind::Quad4, CellKind::Tri3] {
                let m = generate(&half_disc(
                    radial,
                    circ,
                    Grading::Uniform,
                    Grading::Uniform,
                    false,
                    kind,
                ))
                .unwrap();
                let area = invariants(&m, &["arc", "flat"]);
                let widths = arc_widths(&m, "arc", [0.5, 1.0]);
                assert_eq!(widths.len(), circ);
                // the mesh fills exactly the inscribed polygon
                assert!((area - inscribed(1.0, &widths)).abs() < 1e-12);
                if kind == CellKind::Quad4 {
                    errors.push(PI / 2.0 - area);
                    println!(
                    "half_disc {radial}x{circ}: area {area:.12}, error vs pi/2 {:.3e}, cells {}",
                    PI / 2.0 - area,
                    m.cells.len()
                );
                }
            }
        }
        // second order convergence of the polygonal area
        for w in errors.windows(2) {
            let rate = (w[0] / w[1]).log2();
            assert!((rate - 2.0).abs() < 0.01, "rate {rate}");
        }
    }

    #[test]
    fn half_disc_sets_exact_on_circle_and_diameter() {
        for upper in [false, true] {
            for kind in [CellKind::Quad4, CellKind::Tri3] {
                let m = generate(&half_disc(
                    7,
                    23,
                    Grading::Geometric { ratio: 0.3 },
                    Grading::Center { ratio: 5.0 },
                    upper,
                    kind,
                ))
                .unwrap();
                invariants(&m, &["arc", "flat"]);
                let c = m.node_sets["center"][0];
                assert_eq!(m.nodes[c], [0.5, 1.0]);
                for &n in &m.node_sets["arc"] {
                    let p = m.nodes[n];
                    let r = (p[0] - 0.5).hypot(p[1] - 1.0);
                    assert!((r - 1.0).abs() <= 4.5e-16, "arc node at radius {r}");
                    assert!(if upper { p[1] >= 1.0 } else { p[1] <= 1.0 });
                }
                for &n in &m.node_sets["flat"] {
                    assert_eq!(m.nodes[n][1], 1.0, "flat node off the diameter");
                }
                // the arc ends are exactly on the diameter
                let ends: Vec<f64> = m.node_sets["flat"].iter().map(|&n| m.nodes[n][0]).collect();
                assert!(ends.contains(&-0.5) && ends.contains(&1.5));
            }
        }
    }

    #[test]
    fn half_disc_center_grading_mirror_symmetric_and_ratio() {
        let m = generate(&half_disc(
            12,
            40,
            Grading::Geometric { ratio: 0.25 },
            Grading::Center { ratio: 6.0 },
            false,
            CellKind::Quad4,
        ))
        .unwrap();
        let w = arc_widths(&m, "arc", [0.5, 1.0]);
        let measured = w[0] / w[19];
        println!("half_disc center(6): measured end/middle {measured}");
        assert!((measured - 6.0).abs() < 1e-9);
        // radial grading along the diameter: last (at the arc) / first (centre)
        let flat = lengths(&m, "flat");
        let measured = flat[0] / flat[11];
        println!("half_disc radial geometric(0.25): measured last/first {measured}");
        assert!((measured - 0.25).abs() < 1e-9);
        // every cell has a mirror image about x = 0.5
        let key = |pts: Vec<[f64; 2]>| {
            let mut v: Vec<(i64, i64)> = pts
                .iter()
                .map(|p| ((p[0] * 1e9).round() as i64, (p[1] * 1e9).round() as i64))
                .collect();
            v.sort();
            v
        };
        let cells: BTreeSet<_> = m
            .cells
            .iter()
            .map(|c| key(c.nodes.iter().map(|&n| m.nodes[n]).collect()))
            .collect();
        for c in &m.cells {
            let mirrored = key(c
                .nodes
                .iter()
                .map(|&n| [1.0 - m.nodes[n][0], m.nodes[n][1]])
                .collect());
            assert!(cells.contains(&mirrored), "no mirror image of {c:?}");
        }
    }

    /// The Hertz cylinder configuration of VERIFICATION-CASES (a = 0.1 R):
    /// elements across the contact half-width and element quality.
    #[test]
    fn half_disc_hertz_contact_resolution_and_quality() {
        let r = 8.0;
        let a = 0.1 * r;
        for (radial, circ, rg, cr) in [(30, 80, 0.05, 30.0), (20, 64, 0.1, 30.0)] {
            let spec = MeshSpec::HalfDisc {
                center: [0.0, r],
                radius: r,
                radial,
                circumferential: circ,
                radial_grading: Grading::Geometric { ratio: rg },
                circumferential_grading: Grading::Center { ratio: cr },
                upper: false,
                kind: CellKind::Quad4,
            };
            let m = generate(&spec).unwrap();
            let area = invariants(&m, &["arc", "flat"]);
            let in_contact = m.edge_sets["arc"]
                .iter()
                .filter(|e| {
                    e.iter()
                        .all(|&n| (0.0..=a + 1e-12).contains(&m.nodes[n][0]))
                })
                .count();
            let s = summary(&m).unwrap();
            let arc: BTreeSet<usize> = m.node_sets["arc"].iter().copied().collect();
            let near_pole = |c: &ctc_engine::mesh::CellRef| {
                c.nodes
                    .iter()
                    .all(|&n| m.nodes[n][0].hypot(m.nodes[n][1]) < a)
            };
            // cells within a of the pole, and those of them on the surface
            let near: Vec<_> = m.cells.iter().filter(near_pole).collect();
            let surface: Vec<_> = near
                .iter()
                .filter(|c| c.nodes.iter().any(|n| arc.contains(n)))
                .collect();
            let q_near: Vec<_> = near.iter().map(|c| cell_quality(&m, *c)).collect();
            let q_surf: Vec<_> = surface.iter().map(|c| cell_quality(&m, **c)).collect();
            let max_ar = |q: &[ctc_engine::mesh::quality::CellQuality]| {
                q.iter().map(|q| q.aspect_ratio).fold(0.0, f64::max)
            };
            let min_angle = |q: &[ctc_engine::mesh::quality::CellQuality]| {
                q.iter().map(|q| q.min_angle).fold(180.0, f64::min)
            };
            println!(
                "hertz half_disc R={r} radial={radial} geometric({rg}) circ={circ} center({cr}): \
             {} nodes, {} cells, {} arc edges in [0, a]; aspect ratio {:.3}..{:.3}, angles \
             {:.1}..{:.1} deg; within a of the pole: {} cells, max aspect {:.3}, min angle \
             {:.1} deg; surface cells there: {}, max aspect {:.3}, min angle {:.1} deg; \
             area error vs pi R^2/2 {:.2e}",
                m.nodes.len(),
                m.cells.len(),
                in_contact,
                s.min_aspect_ratio,
                s.max_aspect_ratio,
                s.min_angle,
                s.max_angle,
                near.len(),
                max_ar(&q_near),
                min_angle(&q_near),
                surface.len(),
                max_ar(&q_surf),
                min_angle(&q_surf),
                (PI * r * r / 2.0 - area) / (PI * r * r / 2.0)
            );
            assert!(
                (10..=25).contains(&in_contact),
                "{in_contact} elements across a"
            );
            assert!(near.len() > 50);
            assert!(max_ar(&q_near) < 3.0, "contact zone aspect");
            assert!(min_angle(&q_near) > 20.0, "contact zone angle");
            // the contact surface: regular quads, about square
            assert!(surface.iter().all(|c| c.kind == CellKind::Quad4));
            assert!(max_ar(&q_surf) < 2.5 && min_angle(&q_surf) > 85.0);
            assert!(s.min_angle > 20.0 && s.max_angle < 135.0, "{s:?}");
            // the worst cells are the thin arc-layer cells at the coarse ends of
            // the arc, as asked by the gradings (end arc width / arc layer depth)
            assert!(s.max_aspect_ratio < 30.0, "{s:?}");
        }
    }

    #[test]
    fn half_disc_hub_is_reasonable_triangles() {
        // a strongly graded arc: without coarsening the hub would be a fan of
        // 80 slivers of 2.25 degrees and less
        let m = generate(&half_disc(
            20,
            80,
            Grading::Uniform,
            Grading::Center { ratio: 10.0 },
            false,
            CellKind::Quad4,
        ))
        .unwrap();
        invariants(&m, &["arc", "flat"]);
        let hub: Vec<_> = m
            .cells
            .iter()
            .filter(|c| c.nodes[0] == m.node_sets["center"][0])
            .collect();
        let worst = hub
            .iter()
            .map(|c| cell_quality(&m, *c).min_angle)
            .fold(180.0, f64::min);
        println!(
            "hub: {} triangles, smallest angle {worst:.1} deg",
            hub.len()
        );
        assert!((3..=8).contains(&hub.len()));
        assert!(worst > 15.0);
        let s = summary(&m).unwrap();
        println!("half_disc 20x80 center(10): {s:?}");
        // the arc layer is 0.05 deep for arc divisions of 0.01 at the pole, as
        // the gradings ask: aspect 5, and a transition triangle in the layer
        // below is as thin
        assert!(s.max_aspect_ratio < 5.5 && s.min_angle > 10.0, "{s:?}");
    }

    #[test]
    fn quarter_disc_sets_area_and_pole_grading() {
        for upper in [false, true] {
            for kind in [CellKind::Quad4, CellKind::Tri3] {
                let center = [0.0, 2.0];
                let m = generate(&MeshSpec::QuarterDisc {
                    center,
                    radius: 2.0,
                    radial: 10,
                    circumferential: 20,
                    radial_grading: Grading::Geometric { ratio: 0.2 },
                    circumferential_grading: Grading::Geometric { ratio: 0.1 },
                    upper,
                    kind,
                })
                .unwrap();
                let area = invariants(&m, &["arc", "axis", "flat"]);
                let w = arc_widths(&m, "arc", center);
                assert!((area - inscribed(2.0, &w)).abs() < 1e-12);
                assert!(area < PI && (PI - area) / PI < 1e-2, "area {area}");
                // arc walk runs counter-clockwise; the pole (axis end) is first
                // for the lower quarter and last for the upper
                let (at_flat, at_axis) = if upper { (w[0], w[19]) } else { (w[19], w[0]) };
                let measured = at_axis / at_flat;
                assert!((measured - 0.1).abs() < 1e-9, "measured {measured}");
                for &n in &m.node_sets["axis"] {
                    assert_eq!(m.nodes[n][0], 0.0);
                }
                for &n in &m.node_sets["flat"] {
                    assert_eq!(m.nodes[n][1], 2.0);
                }
                assert!(m.nodes.iter().all(|p| p[0] >= 0.0));
                assert!(m
                    .nodes
                    .iter()
                    .all(|p| if upper { p[1] >= 2.0 } else { p[1] <= 2.0 }));
                let s = summary(&m).unwrap();
                if kind == CellKind::Quad4 {
                    println!("quarter_disc 10x20 upper={upper}: area {area:.10}, {s:?}");
                }
                // Tri3 cuts the aspect-5 quads at the coarse flat end in two
                let limit = if kind == CellKind::Quad4 { 20.0 } else { 10.0 };
                assert!(s.min_angle > limit, "{s:?}");
            }
        }
    }

    #[test]
    fn quarter_disc_single_division() {
        let m = generate(&MeshSpec::QuarterDisc {
            center: [0.0, 0.0],
            radius: 1.0,
            radial: 1,
            circumferential: 1,
            radial_grading: Grading::Uniform,
            circumferential_grading: Grading::Uniform,
            upper: true,
            kind: CellKind::Quad4,
        })
        .unwrap();
        let area = invariants(&m, &["arc", "axis", "flat"]);
        assert_eq!(m.cells.len(), 1);
        assert!((area - 0.5).abs() < 1e-15);
    }

    #[test]
    fn annulus_sector_and_full_ring() {
        let center = [1.0, -1.0];
        for kind in [CellKind::Quad4, CellKind::Tri3] {
            let m = generate(&MeshSpec::Annulus {
                center,
                inner: 1.0,
                outer: 2.0,
                start_angle: -30.0,
                end_angle: 90.0,
                radial: 8,
                circumferential: 16,
                radial_grading: Grading::Geometric { ratio: 0.5 },
                kind,
            })
            .unwrap();
            let area = invariants(&m, &["inner", "outer", "start", "end"]);
            let w = arc_widths(&m, "outer", center);
            let exact = inscribed(2.0, &w) - inscribed(1.0, &w);
            assert!((area - exact).abs() < 1e-12);
            let start = lengths(&m, "start");
            assert!((start[7] / start[0] - 0.5).abs() < 1e-9);
            let top = m.nodes[m.node_sets["outer"][0]];
            let s = summary(&m).unwrap();
            println!("annulus 8x16 {kind:?}: area {area:.12} (polygon {exact:.12}), {s:?} {top:?}");
            // the end ray at 90 degrees is exactly vertical
            for &n in &m.node_sets["end"] {
                assert_eq!(m.nodes[n][0], 1.0);
            }
        }
        let m = generate(&MeshSpec::Annulus {
            center,
            inner: 0.5,
            outer: 1.0,
            start_angle: 45.0,
            end_angle: 405.0,
            radial: 3,
            circumferential: 24,
            radial_grading: Grading::Uniform,
            kind: CellKind::Quad4,
        })
        .unwrap();
        let area = invariants(&m, &["inner", "outer"]);
        assert_eq!(m.nodes.len(), 4 * 24);
        let exact = 12.0 * (1.0 - 0.25) * (2.0 * PI / 24.0).sin();
        assert!((area - exact).abs() < 1e-12, "{area} {exact}");
        assert!(!m.node_sets.contains_key("start"));
    }

    #[test]
    fn select_on_half_disc_diameter_and_box_matches_sets() {
        use ctc_engine::mesh::select::{select_edges, select_nodes, Selection};
        let m = generate(&half_disc(
            9,
            31,
            Grading::Geometric { ratio: 0.2 },
            Grading::Center { ratio: 4.0 },
            false,
            CellKind::Tri3,
        ))
        .unwrap();
        let all: Vec<usize> = (0..m.nodes.len()).collect();
        let boundary = m.boundary_edges(0..m.cells.len());
        assert_eq!(
            select_nodes(&m, &all, &Selection::YEquals(1.0)),
            m.node_sets["flat"]
        );
        let mut flat = select_edges(&m, &boundary, &Selection::YEquals(1.0));
        let mut expected = m.edge_sets["flat"].clone();
        flat.sort();
        expected.sort();
        assert_eq!(flat, expected);
        // a box around the pole (0.5, 0): arc nodes only, and arc edges
        let b = Selection::Box {
            min: [0.3, -0.1],
            max: [0.7, 0.03],
        };
        let nodes = select_nodes(&m, &all, &b);
        assert!(!nodes.is_empty());
        assert!(nodes.iter().all(|n| m.node_sets["arc"].contains(n)));
        let edges = select_edges(&m, &boundary, &b);
        assert_eq!(edges.len(), nodes.len() - 1);
        let pole = select_nodes(&m, &all, &Selection::Nearest([0.5, -1.0]));
        assert_eq!(pole.len(), 1);
        // 31 divisions: no node at the pole, the nearest is next to it
        let dx = |n: usize| (m.nodes[n][0] - 0.5).abs();
        assert!(m.node_sets["arc"].iter().all(|&n| dx(n) >= dx(pole[0])));
    }

    #[test]
    fn generators_reject_bad_specs_without_panicking() {
        let bad = [
            half_disc(
                0,
                10,
                Grading::Uniform,
                Grading::Uniform,
                false,
                CellKind::Quad4,
            ),
            half_disc(
                3,
                1,
                Grading::Uniform,
                Grading::Uniform,
                false,
                CellKind::Quad4,
            ),
            half_disc(
                3,
                10,
                Grading::Geometric { ratio: -1.0 },
                Grading::Uniform,
                false,
                CellKind::Quad4,
            ),
            half_disc(
                usize::MAX,
                usize::MAX,
                Grading::Uniform,
                Grading::Uniform,
                false,
                CellKind::Quad4,
            ),
            MeshSpec::HalfDisc {
                center: [0.0, f64::NAN],
                radius: 1.0,
                radial: 2,
                circumferential: 4,
                radial_grading: Grading::Uniform,
                circumferential_grading: Grading::Uniform,
                upper: false,
                kind: CellKind::Tri3,
            },
            MeshSpec::QuarterDisc {
                center: [0.0, 0.0],
                radius: -1.0,
                radial: 2,
                circumferential: 4,
                radial_grading: Grading::Uniform,
                circumferential_grading: Grading::Uniform,
                upper: false,
                kind: CellKind::Tri3,
            },
            MeshSpec::QuarterDisc {
                center: [0.0, 0.0],
                radius: 1.0,
                radial: 2,
                circumferential: 0,
                radial_grading: Grading::Uniform,
                circumferential_grading: Grading::Uniform,
                upper: false,
                kind: CellKind::Tri3,
            },
            MeshSpec::Rectangle {
                origin: [0.0, 0.0],
                size: [1.0, 1.0],
                divisions: [2, 2],
                grading: [
                    Grading::Center {
                        ratio: f64::INFINITY,
                    },
                    Grading::Uniform,
                ],
                kind: CellKind::Quad4,
            },
        ];
        let annulus =
            |inner: f64, outer: f64, start: f64, end: f64, circ: usize| MeshSpec::Annulus {
                center: [0.0, 0.0],
                inner,
                outer,
                start_angle: start,
                end_angle: end,
                radial: 2,
                circumferential: circ,
                radial_grading: Grading::Uniform,
                kind: CellKind::Quad4,
            };
        let bad_annuli = [
            annulus(2.0, 1.0, 0.0, 90.0, 4),
            annulus(0.0, 1.0, 0.0, 90.0, 4),
            annulus(1.0, 2.0, 90.0, 0.0, 4),
            annulus(1.0, 2.0, 0.0, 400.0, 8),
            annulus(1.0, 2.0, 0.0, 360.0, 2),
            annulus(1.0, 2.0, 0.0, 270.0, 1),
            annulus(1.0, 2.0, 0.0, f64::NAN, 4),
        ];
        for spec in bad.iter().chain(bad_annuli.iter()) {
            let e = generate(spec).expect_err("accepted a bad spec");
            assert!(e.line.is_none());
            assert!(!e.message.is_empty());
            println!("{}", e.message);
        }
    }
}
