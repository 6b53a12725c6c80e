//! Same deck, same results, bit for bit, in 2D and 3D. (The engine's
//! threads — element loop, low-rank solves, `solve/parallel.rs` — compute
//! every value as the serial code does, and faer runs sequentially
//! (`Par::Seq`), so the thread count cannot change a bit (unit tests in
//! `assembly.rs` and `linalg/direct.rs`, `cli::threads_do_not_change_...`);
//! a second compile checks that lowering and mesh generation are
//! deterministic too.)

use ctc_engine::geom::Dimension;
use ctc_engine::model::AnyModel;
use ctc_engine::solve::{IncrementView, Observer};
use nalgebra::Const;
use std::path::Path;

/// Collects the raw bits of every converged state.
#[derive(Default)]
struct Bits(Vec<u64>);

impl<const D: usize> Observer<D> for Bits
where
    Const<D>: Dimension<D>,
{
    fn converged(&mut self, v: &IncrementView<'_, D>) -> Result<(), String> {
        for u in v.displacement.iter().chain(v.reaction.iter()) {
            self.0.extend(u.iter().map(|x| x.to_bits()));
        }
        for pair in v.contact {
            for n in pair {
                self.0.push(n.gap.to_bits());
                self.0.extend(n.force.iter().map(|x| x.to_bits()));
            }
        }
        self.0.extend(v.residuals.iter().map(|r| r.to_bits()));
        Ok(())
    }
}

#[test]
fn cylinder_on_block_twice_gives_identical_bits() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/cylinder_on_block.ctc");
    let src = ctc_lang::Source::read(&path).unwrap();
    let model = ctc_lang::compile(&src).unwrap_or_else(|d| panic!("{}", d.render(&src)));
    let mut first = Bits::default();
    let mut second = Bits::default();
    ctc_engine::solve::run(&model, &mut first).unwrap();
    // A second compile too: lowering and mesh generation must be deterministic as well.
    let model2 = ctc_lang::compile(&src).unwrap_or_else(|d| panic!("{}", d.render(&src)));
    ctc_engine::solve::run(&model2, &mut second).unwrap();
    assert!(!first.0.is_empty());
    assert_eq!(first.0.len(), second.0.len());
    let differing = first
        .0
        .iter()
        .zip(&second.0)
        .filter(|(a, b)| a != b)
        .count();
    assert_eq!(
        differing, 0,
        "{differing} values differ between two identical runs"
    );
}

#[test]
fn solid_decks_twice_give_identical_bits() {
    // 3D: hex8 Hertz block against an analytical sphere, and the 3D
    // friction block (stick, then slip on a plane). The Hertz block 10^3
    // rather than the example's 16^3 (the same comparison of every bit;
    // the four 16^3 runs were most of this test's 44 s of wall under
    // load 13-17; the example runs as written in `examples.rs`)
    for (deck, edit) in [
        (
            "hertz_sphere_3d.ctc",
            Some(("divisions = (16, 16, 16)", "divisions = (10, 10, 10)")),
        ),
        ("friction_block_3d.ctc", None),
    ] {
        let path = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("examples")
            .join(deck);
        let mut src = ctc_lang::Source::read(&path).unwrap();
        if let Some((from, to)) = edit {
            assert!(src.text.contains(from), "{deck}: `{from}` not found");
            src = ctc_lang::Source::new(&path, src.text.replace(from, to));
        }
        let compile = || match ctc_lang::compile_any(&src) {
            Ok(AnyModel::D3(m)) => m,
            Ok(AnyModel::D2(_)) => panic!("{deck} is not 3d"),
            Err(d) => panic!("{}", d.render(&src)),
        };
        let mut first = Bits::default();
        let mut second = Bits::default();
        ctc_engine::solve::run(&compile(), &mut first).unwrap();
        ctc_engine::solve::run(&compile(), &mut second).unwrap();
        assert!(first.0.len() > 1000, "{deck}");
        assert!(first.0 == second.0, "{deck}: two identical runs differ");
    }
}
