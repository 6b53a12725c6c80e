use ctc_engine::mesh::generate::{generate, Grading, MeshSpec};
use ctc_engine::mesh::{quality, CellKind, Mesh};
use std::io::Write;

fn dump(name: &str, m: &Mesh) {
    let mut f = std::fs::File::create(format!("/tmp/meshviz/{name}.txt")).unwrap();
    writeln!(f, "{}", m.nodes.len()).unwrap();
    for p in &m.nodes { writeln!(f, "{} {}", p[0], p[1]).unwrap(); }
    for c in &m.cells { writeln!(f, "{}", c.node_slice().iter().map(|x| x.to_string()).collect::<Vec<_>>().join(" ")).unwrap(); }
    let s = quality::summary(m).unwrap();
    println!("{name}: nodes {} cells {} {:?}", m.nodes.len(), m.cells.len(), s);
}

#[test]
fn scratch() {
    let hd = |radial, circ, rg, cg, kind| MeshSpec::HalfDisc { center: [0.0, 1.0], radius: 1.0, radial, circumferential: circ, radial_grading: rg, circumferential_grading: cg, upper: false, kind };
    dump("hd_uniform", &generate(&hd(10, 40, Grading::Uniform, Grading::Uniform, CellKind::Quad4)).unwrap());
    dump("hd_hertz", &generate(&hd(30, 80, Grading::Geometric{ratio: 0.05}, Grading::Center{ratio: 30.0}, CellKind::Quad4)).unwrap());
    dump("hd_hertz_tri", &generate(&hd(30, 80, Grading::Geometric{ratio: 0.05}, Grading::Center{ratio: 30.0}, CellKind::Tri3)).unwrap());
    dump("qd", &generate(&MeshSpec::QuarterDisc { center: [0.0, 1.0], radius: 1.0, radial: 20, circumferential: 40, radial_grading: Grading::Geometric{ratio:0.1}, circumferential_grading: Grading::Geometric{ratio: 0.1}, upper: false, kind: CellKind::Quad4 }).unwrap());
    dump("ann", &generate(&MeshSpec::Annulus { center: [0.0, 0.0], inner: 1.0, outer: 2.0, start_angle: 0.0, end_angle: 90.0, radial: 8, circumferential: 16, radial_grading: Grading::Uniform, kind: CellKind::Tri3 }).unwrap());
}
