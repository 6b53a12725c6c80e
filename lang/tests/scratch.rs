#[test]
fn scratch() {
    let cases = [
        "analysis { dimension = plane_strain }\nset a = b.nodes(x = 0\nstep { time = 0 .. 1 }",
        "analysis { dimension = plane_strain }\nstep s { time = 0 .. }",
        "analysis { dimension = plane_strain }\ntool t = circle { center = (0, 1 radius = 1 }",
        "analysis { dimension = plane_strain }\ncontact a.b punch { }",
        "analysis { dimension = plane_strain }\nmaterial { elastic { E = 1 nu = 0.3 } }",
        "analysis { dimension = plane_strain }\nbody b { mesh = file part.msh }",
        "analysis { dimension = plane_strain }\nbody b { mesh = file \"part.msh }",
        "analysis { dimension = plane_strain, thickness = 1 }",
        "analysis { dimension = plane_strain }\nfix b.c { ux; uy }",
        "analysis { dimension = plane_strain }\nforce b.node(near(0,0)) { fy = -1e }",
        "analysis ( dimension = plane_strain )",
        "analysis { dimension = plane_strain }\nstep s { time = 0 .. 1 } }\nstep t { time = 1 .. 2 }",
        "analysis { dimension = plane_strain }\n@",
        "analysis { dimension = plane_strain }\ntool t circle { }",
        "analysis { dimension = plane_strain }\nset = b.top",
    ];
    for c in cases {
        let src = ctc_lang::Source::new("x.ctc", c);
        println!("{}\n-----", ctc_lang::check(&src).diagnostics.render(&src));
    }
}
