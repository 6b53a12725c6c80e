//! Distributed 3D linear elasticity on PETSc, checked against a serial faer
//! solve. Run on one rank by `cargo test -p ctc -p ctc-petsc --features
//! ctc/petsc --test mpi_elasticity` (or `cargo test -p ctc-petsc --features
//! petsc`), on two by `bash petsc/mpi-test.sh 2` (`mpirun -n 2` on this
//! binary).
//!
//! Reference: the same discrete problem solved serially (faer sparse
//! Cholesky on the free dofs, natural numbering). Element: trilinear hex8,
//! 2x2x2 Gauss (Hughes, *The Finite Element Method*, 2000, §3.8 and
//! table 3.I.1); isotropic Hooke (E = 1000, nu = 0.3).
//!
//! ```text
//!   z                               clamped at x = 0, gravity b = (0, 0, -1)
//!   |  +---------------------------+
//!   | /|  8 x 4 x 4 hex8, graded  /|
//!   |+---------------------------+ |
//!   ||/                          |/ ---> x   (L = 4, 1 x 1 section)
//!   |+---------------------------+
//! ```
//!
//! Checks: MUMPS LU and CG + GAMG (with the rigid-body near-null space) give
//! the serial solution within their tolerance; the 2-rank solution equals
//! the 1-rank one (each rank also solves the whole problem on its own
//! communicator); the preallocation is exact (no malloc during assembly);
//! ghost updates carry the solution to the interface (strain energy summed
//! over the ranks' cells = the serial one); the partition and numbering are
//! deterministic; typed errors and rank agreement; a finite-strain plastic
//! strip through the engine's Newton loop on [`ctc_petsc::PetscSystem`]
//! (distributed assembly, integration points exchanged at each commit)
//! gives the serial Newton iterations and plastic strains.

#![allow(clippy::needless_range_loop)] // index loops read as the formulas

use ctc_petsc::krylov::near_null_space;
use ctc_petsc::{
    partition_cells, Comm, DistMatrix, DofLayout, Environment, GhostedVector, Krylov, PetscError,
    Preallocation, SolveReport, SolverChoice,
};
use faer::linalg::solvers::Solve;
use faer::sparse::{SparseColMat, Triplet};
use faer::Side;

const E: f64 = 1000.0;
const NU: f64 = 0.3;

/// A structured hex8 box, graded in x (cells grow by 1.2 along x).
struct Box3 {
    coords: Vec<f64>,
    cells: Vec<[usize; 8]>,
    /// Nodes on x = 0.
    clamped: Vec<usize>,
}

fn box_mesh(nx: usize, ny: usize, nz: usize) -> Box3 {
    let grow: f64 = 1.2;
    let total: f64 = (0..nx).map(|i| grow.powi(i as i32)).sum();
    let mut xs = vec![0.0];
    for i in 0..nx {
        xs.push(xs[i] + 4.0 * grow.powi(i as i32) / total);
    }
    let id = |i: usize, j: usize, k: usize| i + (nx + 1) * (j + (ny + 1) * k);
    let mut coords = Vec::new();
    for k in 0..=nz {
        for j in 0..=ny {
            for x in &xs {
                coords.extend([*x, j as f64 / ny as f64, k as f64 / nz as f64]);
            }
        }
    }
    let mut cells = Vec::new();
    for k in 0..nz {
        for j in 0..ny {
            for i in 0..nx {
                cells.push([
                    id(i, j, k),
                    id(i + 1, j, k),
                    id(i + 1, j + 1, k),
                    id(i, j + 1, k),
                    id(i, j, k + 1),
                    id(i + 1, j, k + 1),
                    id(i + 1, j + 1, k + 1),
                    id(i, j + 1, k + 1),
                ]);
            }
        }
    }
    let clamped = (0..coords.len() / 3)
        .filter(|&n| coords[3 * n] == 0.0)
        .collect();
    Box3 {
        coords,
        cells,
        clamped,
    }
}

/// Stiffness (24 x 24, row-major) and body-force vector of one hex8 cell.
fn hex8(x: &[[f64; 3]; 8], b: [f64; 3]) -> (Vec<f64>, [f64; 24]) {
    const REF: [[f64; 3]; 8] = [
        [-1., -1., -1.],
        [1., -1., -1.],
        [1., 1., -1.],
        [-1., 1., -1.],
        [-1., -1., 1.],
        [1., -1., 1.],
        [1., 1., 1.],
        [-1., 1., 1.],
    ];
    let lam = E * NU / ((1.0 + NU) * (1.0 - 2.0 * NU));
    let mu = E / (2.0 * (1.0 + NU));
    let mut d = [[0.0; 6]; 6];
    for i in 0..3 {
        for j in 0..3 {
            d[i][j] = lam;
        }
        d[i][i] += 2.0 * mu;
        d[i + 3][i + 3] = mu;
    }
    let g = 1.0 / 3f64.sqrt();
    let mut k = vec![0.0; 24 * 24];
    let mut f = [0.0; 24];
    for gp in REF {
        let q = [gp[0] * g, gp[1] * g, gp[2] * g];
        let mut dn = [[0.0; 3]; 8]; // dN/dxi
        let mut n = [0.0; 8];
        for (a, r) in REF.iter().enumerate() {
            let s = [1.0 + r[0] * q[0], 1.0 + r[1] * q[1], 1.0 + r[2] * q[2]];
            n[a] = s[0] * s[1] * s[2] / 8.0;
            dn[a] = [
                r[0] * s[1] * s[2] / 8.0,
                s[0] * r[1] * s[2] / 8.0,
                s[0] * s[1] * r[2] / 8.0,
            ];
        }
        let mut j = [[0.0; 3]; 3]; // dx_i/dxi_k
        for a in 0..8 {
            for i in 0..3 {
                for kk in 0..3 {
                    j[i][kk] += x[a][i] * dn[a][kk];
                }
            }
        }
        let det = j[0][0] * (j[1][1] * j[2][2] - j[1][2] * j[2][1])
            - j[0][1] * (j[1][0] * j[2][2] - j[1][2] * j[2][0])
            + j[0][2] * (j[1][0] * j[2][1] - j[1][1] * j[2][0]);
        let mut inv = [[0.0; 3]; 3];
        for r in 0..3 {
            for c in 0..3 {
                let (r1, r2, c1, c2) = ((c + 1) % 3, (c + 2) % 3, (r + 1) % 3, (r + 2) % 3);
                inv[r][c] = (j[r1][c1] * j[r2][c2] - j[r1][c2] * j[r2][c1]) / det;
            }
        }
        // dN/dx_i = sum_k dN/dxi_k dxi_k/dx_i
        let mut bm = [[0.0; 24]; 6];
        for a in 0..8 {
            let mut gx = [0.0; 3];
            for (i, v) in gx.iter_mut().enumerate() {
                *v = (0..3).map(|kk| dn[a][kk] * inv[kk][i]).sum();
            }
            let c = 3 * a;
            bm[0][c] = gx[0];
            bm[1][c + 1] = gx[1];
            bm[2][c + 2] = gx[2];
            bm[3][c] = gx[1];
            bm[3][c + 1] = gx[0];
            bm[4][c + 1] = gx[2];
            bm[4][c + 2] = gx[1];
            bm[5][c] = gx[2];
            bm[5][c + 2] = gx[0];
            for i in 0..3 {
                f[c + i] += n[a] * b[i] * det;
            }
        }
        let mut db = [[0.0; 24]; 6];
        for r in 0..6 {
            for c in 0..24 {
                db[r][c] = (0..6).map(|s| d[r][s] * bm[s][c]).sum();
            }
        }
        for r in 0..24 {
            for c in 0..24 {
                k[24 * r + c] += det * (0..6).map(|s| bm[s][r] * db[s][c]).sum::<f64>();
            }
        }
    }
    (k, f)
}

fn cell_coords(m: &Box3, c: usize) -> [[f64; 3]; 8] {
    let mut x = [[0.0; 3]; 8];
    for (a, &n) in m.cells[c].iter().enumerate() {
        x[a] = [m.coords[3 * n], m.coords[3 * n + 1], m.coords[3 * n + 2]];
    }
    x
}

const GRAVITY: [f64; 3] = [0.0, 0.0, -1.0];

/// Serial reference: faer Cholesky on the free dofs; the full natural vector.
fn serial_solution(m: &Box3) -> Vec<f64> {
    let n_nodes = m.coords.len() / 3;
    let mut free = vec![usize::MAX; 3 * n_nodes];
    let mut nf = 0;
    for n in 0..n_nodes {
        if !m.clamped.contains(&n) {
            for c in 0..3 {
                free[3 * n + c] = nf;
                nf += 1;
            }
        }
    }
    let mut trip = Vec::new();
    let mut rhs = vec![0.0; nf];
    for c in 0..m.cells.len() {
        let (k, f) = hex8(&cell_coords(m, c), GRAVITY);
        let free = &free;
        let dofs: Vec<usize> = m.cells[c]
            .iter()
            .flat_map(|&n| (0..3).map(move |i| free[3 * n + i]))
            .collect();
        for (r, &dr) in dofs.iter().enumerate() {
            if dr == usize::MAX {
                continue;
            }
            rhs[dr] += f[r];
            for (s, &ds) in dofs.iter().enumerate() {
                if ds != usize::MAX {
                    trip.push(Triplet::new(dr, ds, k[24 * r + s]));
                }
            }
        }
    }
    let a = SparseColMat::<usize, f64>::try_new_from_triplets(nf, nf, &trip).expect("pattern");
    let llt = a.sp_cholesky(Side::Lower).expect("SPD");
    let mut x = faer::Mat::<f64>::from_fn(nf, 1, |i, _| rhs[i]);
    llt.solve_in_place(x.as_mut());
    (0..3 * n_nodes)
        .map(|d| {
            if free[d] == usize::MAX {
                0.0
            } else {
                x[(free[d], 0)]
            }
        })
        .collect()
}

/// What a distributed solve gives back.
struct Distributed {
    /// Solution in natural order.
    u: Vec<f64>,
    report: SolveReport,
    /// Strain energy summed over the ranks' own cells with ghost values.
    energy: f64,
    mallocs: usize,
}

/// Assembles the box on `comm` (partitioned in `comm.size()` parts) and
/// solves with `choice`; `nns`: give GAMG the rigid-body modes.
fn distributed<'e>(
    comm: &Comm<'e>,
    m: &Box3,
    choice: SolverChoice,
    prefix: &str,
    nns: bool,
) -> Result<Distributed, PetscError> {
    let n_nodes = m.coords.len() / 3;
    let part = partition_cells(&m.cells, n_nodes, comm.size(), 4)?;
    let layout = DofLayout::new(&m.cells, &part, n_nodes, comm.size(), comm.rank(), 3)?;
    let pre = Preallocation::from_cells(&layout, &m.cells);
    let mut a = DistMatrix::new(comm, &layout, &pre)?;
    let mut b = GhostedVector::new(comm, &layout)?;
    let mut kes = Vec::new();
    b.local_mut(|local| -> Result<(), PetscError> {
        for &c in &layout.cells {
            let (k, f) = hex8(&cell_coords(m, c), GRAVITY);
            let dofs = layout.cell_dofs(&m.cells[c]);
            a.add(&dofs, &dofs, &k)?;
            for (a_node, &n) in m.cells[c].iter().enumerate() {
                let lb = layout
                    .local_block(n)
                    .expect("a node of an own cell is local");
                for i in 0..3 {
                    local[3 * lb + i] += f[3 * a_node + i];
                }
            }
            kes.push(k);
        }
        Ok(())
    })??;
    b.accumulate_ghosts()?;
    a.assemble()?;
    let (mallocs, _) = a.allocation()?;
    let x0 = GhostedVector::new(comm, &layout)?;
    let owned_clamped: Vec<usize> = m
        .clamped
        .iter()
        .copied()
        .filter(|&n| layout.node_owner[n] == comm.rank())
        .collect();
    let rows = layout.cell_dofs(&owned_clamped);
    a.zero_rows_columns(&rows, 1.0, &x0, &mut b)?;
    if nns {
        near_null_space(comm, &layout, &mut a, &m.coords)?;
    }
    let mut ksp = Krylov::new(comm, &a, choice, prefix)?;
    let mut x = GhostedVector::new(comm, &layout)?;
    let report = ksp.solve(&b, &mut x)?;
    x.update_ghosts()?;
    let local_energy = x.with_local(|u| {
        let mut e = 0.0;
        for (ci, &c) in layout.cells.iter().enumerate() {
            let mut ue = Vec::with_capacity(24);
            for &n in &m.cells[c] {
                let lb = layout.local_block(n).expect("local");
                ue.extend_from_slice(&u[3 * lb..3 * lb + 3]);
            }
            for r in 0..24 {
                for s in 0..24 {
                    e += 0.5 * ue[r] * kes[ci][24 * r + s] * ue[s];
                }
            }
        }
        e
    })?;
    let energy = comm.sum(local_energy);
    let u = layout.to_natural(&x.gather_all()?);
    Ok(Distributed {
        u,
        report,
        energy,
        mallocs,
    })
}

fn rel_diff(a: &[f64], b: &[f64]) -> f64 {
    let scale = b.iter().fold(0.0f64, |s, v| s.max(v.abs()));
    a.iter()
        .zip(b)
        .fold(0.0f64, |s, (x, y)| s.max((x - y).abs()))
        / scale
}

/// Serial strain energy 0.5 u.K u, cell by cell.
fn serial_energy(m: &Box3, u: &[f64]) -> f64 {
    let mut e = 0.0;
    for c in 0..m.cells.len() {
        let (k, _) = hex8(&cell_coords(m, c), GRAVITY);
        let ue: Vec<f64> = m.cells[c]
            .iter()
            .flat_map(|&n| (0..3).map(move |i| u[3 * n + i]))
            .collect();
        for r in 0..24 {
            for s in 0..24 {
                e += 0.5 * ue[r] * k[24 * r + s] * ue[s];
            }
        }
    }
    e
}

struct Checks {
    passed: usize,
    failed: usize,
    rank: usize,
}

impl Checks {
    fn check(&mut self, comm: &Comm<'_>, name: &str, ok: bool, detail: String) {
        let ok = comm.all(ok);
        if self.rank == 0 {
            println!("{} {name}: {detail}", if ok { "ok    " } else { "FAILED" });
        }
        if ok {
            self.passed += 1;
        } else {
            self.failed += 1;
        }
    }
}

/// A finite-strain J2-plastic strip (plane strain, 8 x 4 quad4, linear
/// hardening) compressed by 6 % in 4 increments, solved serially (faer)
/// and through [`PetscSystem`] on all ranks: each rank evaluates the
/// integration points of its cells and the ranks exchange them at each
/// commit, so every rank must see the serial plastic strains.
///
/// ```text
///   y   uy = -0.06 t on the top
///   |  +--------+--------+
///   |  | 8 x 4 quad4     |  E = 200e3, nu = 0.3, sigma_y = 250, H = 1000
///   |  +--------+--------+
///   |  uy = 0 bottom, ux = 0 left
/// ```
fn plastic_strip(env: &Environment, t: &mut Checks) {
    use ctc_engine::model::{Hardening, Kinematics, MaterialLaw};
    use ctc_engine::solve::run_with;
    use ctc_engine::testkit::grid::{grid, grid_node};
    use ctc_engine::testkit::{ramp, ModelBuilder, Recorder};
    use ctc_petsc::PetscSystem;
    let world = env.world();
    let (nx, ny) = (8, 4);
    let bottom: Vec<usize> = (0..=nx).map(|i| grid_node(nx, i, 0)).collect();
    let top: Vec<usize> = (0..=nx).map(|i| grid_node(nx, i, ny)).collect();
    let left: Vec<usize> = (0..=ny).map(|j| grid_node(nx, 0, j)).collect();
    let model = ModelBuilder::plane_strain()
        .material(
            "steel",
            MaterialLaw::ElastoPlastic {
                young: 200e3,
                poisson: 0.3,
                hardening: Hardening::Linear {
                    yield_stress: 250.0,
                    modulus: 1000.0,
                },
                viscosity: None,
            },
        )
        .body(
            "strip",
            grid(nx, ny, [0.0, 0.0], [2.0, 1.0], 0.1, 7, false),
            "steel",
        )
        .kinematics(Kinematics::Finite)
        .fix(bottom.clone(), 1)
        .fix(left, 0)
        .displace(top, 1, ramp(0.0, 1.0, -0.06))
        .step("press", 1.0, 4)
        .build();
    let mut serial = Recorder::default();
    let s = run_with(&model, &mut serial, None, None);
    let mut dist = Recorder::default();
    let d = PetscSystem::new(env, &model, SolverChoice::MumpsLu, "plastic_")
        .map_err(|e| e.to_string())
        .and_then(|system| {
            run_with(&model, &mut dist, None, Some(Box::new(system))).map_err(|e| e.message)
        });
    let ok = s.is_ok() && d.is_ok() && dist.increments.len() == serial.increments.len();
    let (mut dep, mut ep_max, mut df) = (f64::INFINITY, 0.0f64, f64::INFINITY);
    let mut same_iterations = false;
    if ok {
        same_iterations = serial
            .increments
            .iter()
            .zip(&dist.increments)
            .all(|(a, b)| a.iterations() == b.iterations());
        let (a, b) = (serial.last(), dist.last());
        ep_max = a
            .points
            .iter()
            .flatten()
            .fold(0.0f64, |m, p| m.max(p.history.ep));
        dep = a
            .points
            .iter()
            .flatten()
            .zip(b.points.iter().flatten())
            .fold(0.0f64, |m, (p, q)| {
                m.max((p.history.ep - q.history.ep).abs())
            })
            / ep_max;
        let (fa, fb) = (a.reaction_of(&bottom)[1], b.reaction_of(&bottom)[1]);
        df = (fa - fb).abs() / fa.abs();
    }
    t.check(
        &world,
        "plastic_finite_strain_points_are_the_serial_ones",
        ok && same_iterations && ep_max > 0.01 && dep < 1e-9 && df < 1e-9,
        format!(
            "runs {:?} / {:?}; same Newton iterations {same_iterations}; largest ep \
             {ep_max:.6e}, rel. diff of ep {dep:.2e}, of the bottom reaction {df:.2e}",
            s.as_ref().err().map(|e| &e.message),
            d.as_ref().err()
        ),
    );
}

fn main() {
    let env = match Environment::initialize("") {
        Ok(e) => e,
        Err(e) => {
            eprintln!("{e}");
            std::process::exit(1);
        }
    };
    let world = env.world();
    let (rank, size) = (world.rank(), world.size());
    let mut t = Checks {
        passed: 0,
        failed: 0,
        rank,
    };
    if rank == 0 {
        println!("mpi_elasticity on {size} rank(s)");
    }
    let m = box_mesh(8, 4, 4);
    let n_nodes = m.coords.len() / 3;
    let reference = serial_solution(&m);
    let tip = reference.iter().fold(0.0f64, |s, v| s.min(*v));

    // deterministic partition and numbering
    let p1 = partition_cells(&m.cells, n_nodes, 2, 4).expect("metis");
    let p2 = partition_cells(&m.cells, n_nodes, 2, 4).expect("metis");
    let l1 = DofLayout::new(&m.cells, &p1, n_nodes, 2, 0, 3).expect("layout");
    let l2 = DofLayout::new(&m.cells, &p2, n_nodes, 2, 1, 3).expect("layout");
    let parts_count = [0, 1].map(|r| p1.iter().filter(|&&p| p == r).count());
    let mut blocks = l1.node_block.clone();
    blocks.sort_unstable();
    t.check(
        &world,
        "partition_and_numbering_are_deterministic",
        p1 == p2
            && l1.node_block == l2.node_block
            && blocks == (0..n_nodes).collect::<Vec<_>>()
            && parts_count.iter().all(|&c| c > 0),
        format!(
            "METIS 2 parts: {:?} cells, {} ghost nodes on rank 1",
            parts_count,
            l2.ghost_nodes.len()
        ),
    );

    // MUMPS LU on all ranks
    let lu = distributed(&world, &m, SolverChoice::MumpsLu, "lu_", false);
    match &lu {
        Ok(d) => {
            let e = rel_diff(&d.u, &reference);
            t.check(
                &world,
                "mumps_lu_matches_serial_faer",
                e < 1e-10,
                format!("max |u - u_faer| / max |u_faer| = {e:.2e} (tip uz = {tip:.6e})"),
            );
            t.check(
                &world,
                "preallocation_is_exact",
                d.mallocs == 0,
                format!("{} mallocs during assembly", d.mallocs),
            );
            let es = serial_energy(&m, &reference);
            let ee = (d.energy - es).abs() / es;
            t.check(
                &world,
                "ghost_update_gives_the_serial_strain_energy",
                ee < 1e-10,
                format!("energy {:.10e} vs serial {es:.10e}", d.energy),
            );
            let again = distributed(&world, &m, SolverChoice::MumpsLu, "lu_", false)
                .map(|x| x.u)
                .unwrap_or_default();
            // One rank: bit for bit. Several: MUMPS schedules its parallel
            // factorization dynamically, so two solves may differ in the last
            // bits (seen about one run in four on 2 ranks): round-off only.
            let bitwise = again.len() == d.u.len()
                && again
                    .iter()
                    .zip(&d.u)
                    .all(|(a, b)| a.to_bits() == b.to_bits());
            let diff = if again.len() == d.u.len() {
                rel_diff(&again, &d.u)
            } else {
                f64::INFINITY
            };
            t.check(
                &world,
                "same_rank_count_repeats_the_solution",
                if size == 1 { bitwise } else { diff < 1e-13 },
                format!(
                    "two MUMPS solves on the same ranks: bitwise {bitwise}, rel. diff {diff:.1e}"
                ),
            );
        }
        Err(e) => t.check(&world, "mumps_lu_matches_serial_faer", false, e.to_string()),
    }

    // CG + GAMG with and without the near-null space
    let rtol = 1e-10;
    let gamg = distributed(&world, &m, SolverChoice::CgGamg { rtol }, "amg_", true);
    let plain = distributed(
        &world,
        &m,
        SolverChoice::CgGamg { rtol },
        "amgplain_",
        false,
    );
    match (&gamg, &plain) {
        (Ok(g), Ok(p)) => {
            let e = rel_diff(&g.u, &reference);
            t.check(
                &world,
                "cg_gamg_rigid_body_modes_matches_serial_faer",
                e < 1e-7,
                format!(
                    "rtol {rtol:e}: {} iterations ({}), rel. diff {e:.2e}; without near-null space: {} iterations",
                    g.report.iterations, g.report.reason, p.report.iterations
                ),
            );
            t.check(
                &world,
                "rigid_body_modes_help_gamg",
                g.report.iterations < p.report.iterations,
                format!("{} < {}", g.report.iterations, p.report.iterations),
            );
        }
        (g, p) => t.check(
            &world,
            "cg_gamg_rigid_body_modes_matches_serial_faer",
            false,
            format!("{:?} {:?}", g.as_ref().err(), p.as_ref().err()),
        ),
    }

    if env.has_package("hypre") {
        match distributed(&world, &m, SolverChoice::CgHypre { rtol }, "hypre_", false) {
            Ok(h) => {
                let e = rel_diff(&h.u, &reference);
                t.check(
                    &world,
                    "cg_boomeramg_matches_serial_faer",
                    e < 1e-7,
                    format!("{} iterations, rel. diff {e:.2e}", h.report.iterations),
                );
            }
            Err(e) => t.check(
                &world,
                "cg_boomeramg_matches_serial_faer",
                false,
                e.to_string(),
            ),
        }
    } else if rank == 0 {
        println!("skip   cg_boomeramg: this PETSc build has no hypre");
    }

    // 1 rank vs all ranks: every rank solves the whole problem alone too
    if size > 1 {
        let local = env.local();
        let one = distributed(&local, &m, SolverChoice::MumpsLu, "lu1_", false);
        let one_amg = distributed(&local, &m, SolverChoice::CgGamg { rtol }, "amg1_", true);
        match (&lu, &one, &gamg, &one_amg) {
            (Ok(n), Ok(o), Ok(ng), Ok(og)) => {
                let e = rel_diff(&n.u, &o.u);
                let eg = rel_diff(&ng.u, &og.u);
                t.check(
                    &world,
                    "one_and_n_ranks_agree",
                    e < 1e-12 && eg < 1e-7,
                    format!(
                        "MUMPS {e:.2e}; CG+GAMG {eg:.2e} ({} iterations on 1 rank, {} on {size})",
                        og.report.iterations, ng.report.iterations
                    ),
                );
            }
            _ => t.check(
                &world,
                "one_and_n_ranks_agree",
                false,
                "a solve failed".into(),
            ),
        }
    }

    // typed errors
    let diverged = env.insert_options("-div_ksp_max_it 2").and_then(|_| {
        distributed(
            &world,
            &m,
            SolverChoice::CgGamg { rtol: 1e-14 },
            "div_",
            false,
        )
    });
    t.check(
        &world,
        "diverged_krylov_is_a_typed_error",
        matches!(&diverged, Err(PetscError::Diverged { reason_name, iterations: 2, .. }) if reason_name == "DIVERGED_ITS"),
        format!("{:?}", diverged.as_ref().err()),
    );
    let outside = (|| {
        let part = vec![0; m.cells.len()];
        let layout = DofLayout::new(&m.cells, &part, n_nodes, 1, 0, 3)?;
        let local = env.local();
        let mut a = DistMatrix::new(
            &local,
            &layout,
            &Preallocation::from_cells(&layout, &m.cells),
        )?;
        for cell in &m.cells {
            let dofs = layout.cell_dofs(cell);
            a.add(&dofs, &dofs, &vec![1.0; dofs.len() * dofs.len()])?;
        }
        a.assemble()?;
        a.add(&[0], &[3 * n_nodes - 1], &[1.0])
    })();
    t.check(
        &world,
        "value_outside_the_pattern_is_a_typed_error",
        matches!(
            &outside,
            Err(PetscError::Call {
                call: "MatSetValues",
                ..
            })
        ),
        outside
            .as_ref()
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default(),
    );

    // agreement: the last rank fails, every rank sees it
    let local: Result<(), PetscError> = if rank + 1 == size {
        Err(PetscError::Partition("test".into()))
    } else {
        Ok(())
    };
    let agreed = world.agree_failure(local);
    let code = world.agree_failure_code(agreed.as_ref().err().map_or(0, PetscError::code));
    t.check(
        &world,
        "every_rank_agrees_on_a_failure",
        agreed.is_err() && code == 3 && world.agree_converged(rank == 0) == (size == 1),
        format!("error class {code}"),
    );

    plastic_strip(&env, &mut t);

    let failed = world.sum_count(t.failed);
    if rank == 0 {
        println!("{} passed, {} failed", t.passed, t.failed);
    }
    drop(world);
    drop(env);
    if failed > 0 {
        std::process::exit(1);
    }
}
