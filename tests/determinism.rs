//! Same deck, same results, bit for bit.

use ctc_engine::solve::{IncrementView, Observer};
use std::path::Path;

/// Collects the raw bits of every converged state.
#[derive(Default)]
struct Bits(Vec<u64>);

impl Observer for Bits {
    fn converged(&mut self, v: &IncrementView<'_>) -> Result<(), String> {
        for u in v.displacement.iter().chain(v.reaction.iter()) {
            self.0.push(u[0].to_bits());
            self.0.push(u[1].to_bits());
        }
        for pair in v.contact {
            for n in pair {
                self.0.push(n.gap.to_bits());
                self.0.push(n.force[0].to_bits());
                self.0.push(n.force[1].to_bits());
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
