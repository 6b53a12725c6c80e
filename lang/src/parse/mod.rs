//! Parsing.
#![allow(missing_docs)]
/// The pest parser generated from `ctc.pest`.
#[derive(pest_derive::Parser)]
#[grammar = "ctc.pest"]
pub struct CtcParser;

#[cfg(test)]
mod probe {
    use super::*;
    use pest::Parser;
    #[test]
    fn probe() {
        pest::set_error_detail(true);
        let cases = [
            "material steel { elastic { E 210e3 nu = 0.3 } }",
            "material steel { elastic { E = 210e3 nu = 0.3 }",
            "material steel { elastic { E = , nu = 0.3 } }",
            "{",
            "set a = ",
            "set a = b.nodes(x = 0",
            "step s { time = 0 .. }",
            "tool t = circle { center = (0, 1 radius = 1 }",
            "analysis { dimension = plane_strain } body b { mesh = rectangle { size = (1,1) divisions = (1,1) }",
            "contact a.b punch { }",
        ];
        for c in cases {
            match CtcParser::parse(Rule::deck, c) {
                Ok(p) => println!("OK {c}: {p:?}"),
                Err(e) => {
                    println!("ERR {c}\n{e}\n{:?}", e.variant);
                    if let Some(a) = e.parse_attempts() {
                        println!("  expected {:?}\n  unexpected {:?}\n  stacks {:?}\n  pos {}", a.expected_tokens(), a.unexpected_tokens(), a.call_stacks(), a.max_position);
                    }
                }
            }
        }
    }
}
