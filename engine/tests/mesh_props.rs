//! Property tests: the gmsh reader never panics on random or mutated input,
//! and random valid generator specs give valid meshes.

/// Under `mesh::` so that `cargo test -p ctc-engine mesh` selects them.
mod mesh {

    use ctc_engine::mesh::generate::{generate, Grading, MeshSpec};
    use ctc_engine::mesh::gmsh::{parse, parse_bytes};
    use ctc_engine::mesh::quality::cell_area;
    use ctc_engine::mesh::validate::check;
    use ctc_engine::mesh::{CellKind, Mesh, MeshError};
    use proptest::prelude::*;
    use std::collections::BTreeSet;

    const FILES: [&str; 4] = [
        include_str!("data/hand_two_quads_v22.msh"),
        include_str!("data/hand_two_quads_v41.msh"),
        include_str!("data/gmsh_plate_hole_v41.msh"),
        include_str!("data/gmsh_quarter_disc_quads_v22.msh"),
    ];

    /// What the reader promises for any input: an error with a line inside the
    /// file, or a mesh whose numbers are all in range.
    fn reader_contract(text_lines: usize, r: Result<Mesh, MeshError>) -> Result<(), TestCaseError> {
        match r {
            Err(e) => {
                let line = e
                    .line
                    .ok_or_else(|| TestCaseError::fail("error without a line"))?;
                prop_assert!(
                    line >= 1 && line <= text_lines.max(1),
                    "line {line} of {text_lines}: {e}"
                );
            }
            Ok(m) => {
                let n = m.nodes.len();
                prop_assert!(!m.cells.is_empty());
                for c in &m.cells {
                    prop_assert!(c.nodes.iter().all(|&k| k < n));
                    prop_assert!(cell_area(&m, c) >= 0.0);
                }
                for s in m.node_sets.values() {
                    prop_assert!(s.iter().all(|&k| k < n));
                    prop_assert!(s.windows(2).all(|w| w[0] < w[1]));
                }
                for s in m.edge_sets.values() {
                    prop_assert!(s.iter().all(|e| e[0] < n && e[1] < n));
                }
            }
        }
        Ok(())
    }

    /// One edit of a file's lines.
    #[derive(Debug, Clone)]
    enum Mutation {
        Delete(usize),
        Duplicate(usize),
        Swap(usize, usize),
        Replace {
            line: usize,
            token: usize,
            with: String,
        },
        Truncate(usize),
    }

    fn token_strategy() -> impl Strategy<Value = String> {
        prop_oneof![
            any::<i64>().prop_map(|v| v.to_string()),
            (0u64..20).prop_map(|v| v.to_string()),
            any::<f64>().prop_map(|v| v.to_string()),
            Just("18446744073709551616".to_string()),
            Just("nan".to_string()),
            Just("$EndNodes".to_string()),
            Just("$Elements".to_string()),
            Just("$EndEntities".to_string()),
            Just("\"name\"".to_string()),
            Just(String::new()),
            "[ -~]{0,6}",
        ]
    }

    fn mutation_strategy() -> impl Strategy<Value = Mutation> {
        prop_oneof![
            (0usize..200).prop_map(Mutation::Delete),
            (0usize..200).prop_map(Mutation::Duplicate),
            (0usize..200, 0usize..200).prop_map(|(a, b)| Mutation::Swap(a, b)),
            (0usize..200, 0usize..12, token_strategy())
                .prop_map(|(line, token, with)| Mutation::Replace { line, token, with }),
            (0usize..6000).prop_map(Mutation::Truncate),
        ]
    }

    fn apply(text: &str, muts: &[Mutation]) -> String {
        let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
        for m in muts {
            if lines.is_empty() {
                break;
            }
            let n = lines.len();
            match m {
                Mutation::Delete(i) => {
                    lines.remove(i % n);
                }
                Mutation::Duplicate(i) => {
                    let l = lines[i % n].clone();
                    lines.insert(i % n, l);
                }
                Mutation::Swap(a, b) => lines.swap(a % n, b % n),
                Mutation::Replace { line, token, with } => {
                    let mut toks: Vec<String> = lines[line % n]
                        .split_whitespace()
                        .map(str::to_string)
                        .collect();
                    if toks.is_empty() {
                        toks.push(with.clone());
                    } else {
                        let k = token % toks.len();
                        toks[k] = with.clone();
                    }
                    lines[line % n] = toks.join(" ");
                }
                Mutation::Truncate(k) => {
                    let joined = lines.join("\n");
                    let mut cut = (*k).min(joined.len());
                    while !joined.is_char_boundary(cut) {
                        cut -= 1;
                    }
                    lines = joined[..cut].lines().map(str::to_string).collect();
                }
            }
        }
        lines.join("\n")
    }

    fn grading() -> impl Strategy<Value = Grading> {
        prop_oneof![
            Just(Grading::Uniform),
            (0.05f64..20.0).prop_map(|ratio| Grading::Geometric { ratio }),
            (0.05f64..20.0).prop_map(|ratio| Grading::Center { ratio }),
        ]
    }

    fn kind() -> impl Strategy<Value = CellKind> {
        prop_oneof![Just(CellKind::Tri3), Just(CellKind::Quad4)]
    }

    fn point() -> impl Strategy<Value = [f64; 2]> {
        (-100.0f64..100.0, -100.0f64..100.0).prop_map(|(x, y)| [x, y])
    }

    fn spec() -> impl Strategy<Value = MeshSpec> {
        prop_oneof![
            (
                point(),
                (0.01f64..50.0, 0.01f64..50.0),
                (1usize..25, 1usize..25),
                grading(),
                grading(),
                kind()
            )
                .prop_map(|(origin, s, d, gx, gy, kind)| MeshSpec::Rectangle {
                    origin,
                    size: [s.0, s.1],
                    divisions: [d.0, d.1],
                    grading: [gx, gy],
                    kind,
                }),
            (
                point(),
                0.01f64..50.0,
                1usize..25,
                2usize..60,
                grading(),
                grading(),
                any::<bool>(),
                kind()
            )
                .prop_map(|(center, radius, radial, circ, rg, cg, upper, kind)| {
                    MeshSpec::HalfDisc {
                        center,
                        radius,
                        radial,
                        circumferential: circ,
                        radial_grading: rg,
                        circumferential_grading: cg,
                        upper,
                        kind,
                    }
                }),
            (
                point(),
                0.01f64..50.0,
                1usize..25,
                1usize..40,
                grading(),
                grading(),
                any::<bool>(),
                kind()
            )
                .prop_map(|(center, radius, radial, circ, rg, cg, upper, kind)| {
                    MeshSpec::QuarterDisc {
                        center,
                        radius,
                        radial,
                        circumferential: circ,
                        radial_grading: rg,
                        circumferential_grading: cg,
                        upper,
                        kind,
                    }
                }),
            (
                point(),
                0.01f64..10.0,
                1.01f64..5.0,
                -360.0f64..360.0,
                1.0f64..=360.0,
                1usize..12,
                3usize..40,
                grading(),
                kind()
            )
                .prop_map(
                    |(center, inner, factor, start, span, radial, circ, rg, kind)| {
                        MeshSpec::Annulus {
                            center,
                            inner,
                            outer: inner * factor,
                            start_angle: start,
                            end_angle: start + span,
                            radial,
                            circumferential: circ,
                            radial_grading: rg,
                            kind,
                        }
                    }
                ),
        ]
    }

    /// Edge sets every generator defines, by spec.
    fn edge_set_names(spec: &MeshSpec, mesh: &Mesh) -> Vec<String> {
        let names: &[&str] = match spec {
            MeshSpec::Rectangle { .. } => &["bottom", "right", "top", "left"],
            MeshSpec::HalfDisc { .. } => &["arc", "flat"],
            MeshSpec::QuarterDisc { .. } => &["arc", "axis", "flat"],
            MeshSpec::Annulus { .. } if mesh.edge_sets.contains_key("start") => {
                &["inner", "outer", "start", "end"]
            }
            MeshSpec::Annulus { .. } => &["inner", "outer"],
        };
        names.iter().map(|s| s.to_string()).collect()
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

        #[test]
        fn gmsh_parse_never_panics_on_random_bytes(bytes in proptest::collection::vec(any::<u8>(), 0..400)) {
            let lines = bytes.split(|&b| b == b'\n').count();
            reader_contract(lines, parse_bytes(&bytes))?;
            let mut with_header = b"$MeshFormat\n2.2 0 8\n$EndMeshFormat\n".to_vec();
            with_header.extend_from_slice(&bytes);
            let lines = with_header.split(|&b| b == b'\n').count();
            reader_contract(lines, parse_bytes(&with_header))?;
        }

        #[test]
        fn gmsh_parse_never_panics_on_mutated_files(
            file in 0usize..FILES.len(),
            muts in proptest::collection::vec(mutation_strategy(), 1..4),
        ) {
            let text = apply(FILES[file], &muts);
            let lines = text.lines().count();
            reader_contract(lines, parse(&text))?;
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 200, ..ProptestConfig::default() })]

        #[test]
        fn random_generator_specs_give_valid_meshes(spec in spec()) {
            let mesh = generate(&spec).map_err(|e| TestCaseError::fail(e.message))?;
            if let Err(errs) = check(&mesh) {
                return Err(TestCaseError::fail(format!("{spec:?}: {errs:?}")));
            }
            for c in &mesh.cells {
                prop_assert!(cell_area(&mesh, c) > 0.0);
            }
            let boundary: BTreeSet<[usize; 2]> =
                mesh.boundary_edges(0..mesh.cells.len()).into_iter().collect();
            let mut union = BTreeSet::new();
            for name in edge_set_names(&spec, &mesh) {
                let set = &mesh.edge_sets[&name];
                prop_assert!(!set.is_empty(), "{name} empty");
                prop_assert!(!mesh.node_sets[&name].is_empty());
                union.extend(set.iter().copied());
            }
            prop_assert_eq!(boundary, union);
        }
    }
}
