//! Restart points: everything needed to continue a run bit for bit from a
//! converged increment, and its binary file format.
//!
//! A [`Checkpoint`] holds the stepping state (step, time, next increment
//! size, easy-increment counter, increment counter), the committed nodal
//! displacements, the committed contact history of every pair (search
//! memory, multipliers, Lagrange active set), the committed integration
//! points with the time they belong to, and a fingerprint of the model (a
//! restart with a different deck is refused). [`RestartFile`] adds what the
//! result writer needs to append to the same directory (the PVD entries).
//!
//! Format (`restart.bin`, little endian): the magic `CTCRST08`, the
//! dimension (2 or 3; a restart file is read only by a model of the same
//! dimension), then fields in a fixed order, ending with the state of the
//! dynamic integrator (a flag, then velocities, accelerations, committed
//! residual and forces, energies: [`DynamicState`]), the increment
//! predictor's history (a flag, then the step, the start and end times of
//! the last converged increment and the displacements at its start:
//! [`PredictorHistory`]) and the committed beside flags of the
//! node-to-facet penalty pairs (per pair a count, then one byte per slave
//! node: [`PairHistory::beside`]); every `f64` is stored as its 8 bytes,
//! so the values read back are the values written, bit for bit.
//! `CTCRST07` files (the same without the beside flags: they restart
//! cleared), `CTCRST06` files (also without the predictor's history: the
//! first increment after the restart starts from the converged state) and
//! `CTCRST05` files (also without the dynamic state, read as quasi-static
//! restart points) are read; older formats are refused with their version
//! named.

use crate::element::{MaterialPoint, PointState};
use crate::material::History;
use crate::model::Model;
use crate::solve::dynamics::DynamicState;
pub use crate::solve::newton::predictor::PredictorHistory;
use std::path::Path;

/// File magic and format version.
const MAGIC: &[u8; 8] = b"CTCRST08";

/// The previous format: no beside flags.
const MAGIC_07: &[u8; 8] = b"CTCRST07";

/// The format before: no predictor history.
const MAGIC_06: &[u8; 8] = b"CTCRST06";

/// The oldest format read: no dynamic state (read, as quasi-static points).
const MAGIC_05: &[u8; 8] = b"CTCRST05";

/// Values stored per integration point: position (3), volume, strain (6),
/// stress (6), equivalent plastic strain, internal tensor (6).
const POINT_VALUES: usize = 23;

/// Where the stepper continues: the first increment to attempt.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Resume {
    /// Step index (equal to the number of steps when the run is complete).
    pub step: usize,
    /// Time of the last converged state (start of the next increment).
    pub time: f64,
    /// Size of the next increment attempt.
    pub dt: f64,
    /// Consecutive easy increments counted towards growing `dt` back.
    pub easy: usize,
}

/// Committed contact history of one pair.
#[derive(Debug, Clone, PartialEq)]
pub struct PairHistory {
    /// Per slave node: tool entity found at the last converged increment.
    pub entity: Vec<Option<usize>>,
    /// Per slave node: multiplier at the last converged increment.
    pub multiplier: Vec<f64>,
    /// Per slave node: Lagrange active set at the last converged increment.
    pub active: Vec<bool>,
    /// Committed friction state, flattened
    /// ([`crate::contact::friction::FrictionState::committed_values`]).
    pub friction: Vec<f64>,
    /// Per slave node, node-to-facet penalty pairs: the node lay beside the
    /// master at the last converged increment
    /// ([`crate::contact::node_to_facet::DeformablePair::beside`]); empty
    /// for other pairs and in files of a previous format (restart cleared).
    pub beside: Vec<bool>,
}

/// The state of a run of dimension `D` at a converged increment.
#[derive(Debug, Clone, PartialEq)]
pub struct Checkpoint<const D: usize = 2> {
    /// Fingerprint of the model ([`fingerprint`]).
    pub fingerprint: u64,
    /// Converged increments so far (the last one's number).
    pub increment: usize,
    /// Where the stepper continues.
    pub resume: Resume,
    /// Committed nodal displacements.
    pub displacement: Vec<[f64; D]>,
    /// Committed contact history per pair.
    pub pairs: Vec<PairHistory>,
    /// Committed integration points per global cell (empty for linear cells).
    pub points: Vec<Vec<MaterialPoint>>,
    /// Time of the committed integration points (accumulated by the
    /// assembler; kept as is for bit-for-bit rate-dependent updates).
    pub points_time: f64,
    /// Node couplings added to the sparsity pattern by node-to-segment
    /// contact so far (the restarted run starts from the same pattern, so
    /// its factorizations round identically).
    pub couplings: Vec<(usize, usize)>,
    /// The dynamic integrator's committed state (`None`: a model without
    /// dynamic steps, or a file of the previous format).
    pub dynamics: Option<DynamicState>,
    /// The last converged increment for the increment predictor (`None`:
    /// none yet, or a file of a previous format).
    pub predictor: Option<PredictorHistory<D>>,
}

/// A restart file: the solver checkpoint and the result writer's index.
#[derive(Debug, Clone, PartialEq)]
pub struct RestartFile<const D: usize = 2> {
    /// Solver and stepping state.
    pub checkpoint: Checkpoint<D>,
    /// `results.pvd` entries (time, VTU file name) written so far.
    pub pvd: Vec<(f64, String)>,
}

/// 64-bit FNV-1a hash of the model's full description (mesh, materials,
/// loads, steps): two decks that lower to the same model have the same
/// fingerprint.
pub fn fingerprint<const D: usize>(model: &Model<D>) -> u64 {
    use std::fmt::Write as _;
    // the Debug text streamed into the hash (never held: megabytes for
    // a large mesh)
    let mut h = Fnv(0xcbf2_9ce4_8422_2325);
    let _ = write!(h, "{model:?}");
    h.0
}

/// FNV-1a over the text written into it ([`fingerprint`]).
struct Fnv(u64);

impl std::fmt::Write for Fnv {
    fn write_str(&mut self, s: &str) -> std::fmt::Result {
        self.0 = s.bytes().fold(self.0, |h, b| {
            (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
        });
        Ok(())
    }
}

/// Little-endian encoder.
#[derive(Default)]
struct Enc(Vec<u8>);

impl Enc {
    fn u64(&mut self, v: u64) {
        self.0.extend_from_slice(&v.to_le_bytes());
    }
    fn usize(&mut self, v: usize) {
        self.u64(v as u64);
    }
    fn f64(&mut self, v: f64) {
        self.0.extend_from_slice(&v.to_bits().to_le_bytes());
    }
    fn f64s(&mut self, v: &[f64]) {
        self.usize(v.len());
        v.iter().for_each(|x| self.f64(*x));
    }
    fn str(&mut self, s: &str) {
        self.usize(s.len());
        self.0.extend_from_slice(s.as_bytes());
    }
}

/// Little-endian decoder with bounds checks (a truncated or corrupted file
/// gives an error, never a panic).
struct Dec<'a> {
    data: &'a [u8],
    pos: usize,
}

impl Dec<'_> {
    fn bytes(&mut self, n: usize) -> Result<&[u8], String> {
        let end = self
            .pos
            .checked_add(n)
            .filter(|e| *e <= self.data.len())
            .ok_or_else(|| format!("restart file truncated at byte {}", self.pos))?;
        let s = &self.data[self.pos..end];
        self.pos = end;
        Ok(s)
    }
    fn u64(&mut self) -> Result<u64, String> {
        let b = self.bytes(8)?;
        Ok(u64::from_le_bytes(b.try_into().map_err(|_| "bad u64")?))
    }
    fn usize(&mut self) -> Result<usize, String> {
        let v = self.u64()?;
        usize::try_from(v).map_err(|_| format!("restart file: value {v} out of range"))
    }
    /// A length, bounded by the bytes left (each element takes at least
    /// `min_size` bytes).
    fn len(&mut self, min_size: usize) -> Result<usize, String> {
        let n = self.usize()?;
        if n.saturating_mul(min_size.max(1)) > self.data.len() - self.pos {
            return Err(format!(
                "restart file corrupted: length {n} at byte {}",
                self.pos
            ));
        }
        Ok(n)
    }
    fn f64(&mut self) -> Result<f64, String> {
        Ok(f64::from_bits(self.u64()?))
    }
    fn f64s(&mut self) -> Result<Vec<f64>, String> {
        let n = self.len(8)?;
        (0..n).map(|_| self.f64()).collect()
    }
    fn str(&mut self) -> Result<String, String> {
        let n = self.len(1)?;
        String::from_utf8(self.bytes(n)?.to_vec())
            .map_err(|_| "restart file: invalid text".to_string())
    }
}

impl<const D: usize> RestartFile<D> {
    /// The file contents.
    pub fn encode(&self) -> Vec<u8> {
        let mut e = Enc::default();
        e.0.extend_from_slice(MAGIC);
        e.usize(D);
        let c = &self.checkpoint;
        e.u64(c.fingerprint);
        e.usize(c.increment);
        e.usize(c.resume.step);
        e.f64(c.resume.time);
        e.f64(c.resume.dt);
        e.usize(c.resume.easy);
        e.f64s(c.displacement.as_flattened());
        e.usize(c.pairs.len());
        for p in &c.pairs {
            e.usize(p.entity.len());
            for v in &p.entity {
                e.u64(v.map_or(u64::MAX, |x| x as u64));
            }
            e.f64s(&p.multiplier);
            e.usize(p.active.len());
            e.0.extend(p.active.iter().map(|a| u8::from(*a)));
            e.f64s(&p.friction);
        }
        e.usize(c.points.len());
        for cell in &c.points {
            e.usize(cell.len());
            for p in cell {
                let s = &p.state;
                let mut v = s.position.to_vec();
                v.push(s.volume);
                v.extend(s.strain.iter());
                v.extend(s.stress.iter());
                v.push(p.history.ep);
                v.extend(p.history.tensor);
                v.iter().for_each(|x| e.f64(*x));
            }
        }
        e.f64(c.points_time);
        e.usize(self.pvd.len());
        for (t, name) in &self.pvd {
            e.f64(*t);
            e.str(name);
        }
        e.usize(c.couplings.len());
        for &(a, b) in &c.couplings {
            e.usize(a);
            e.usize(b);
        }
        match &c.dynamics {
            None => e.0.push(0),
            Some(s) => {
                e.0.push(1);
                e.0.push(u8::from(s.started));
                e.f64s(&s.v);
                e.f64s(&s.a);
                e.f64s(&s.r0);
                e.usize(s.forces0.len());
                for f in &s.forces0 {
                    e.f64s(f);
                }
                e.f64(s.kinetic0);
                e.f64s(&s.energy);
            }
        }
        match &c.predictor {
            None => e.0.push(0),
            Some(h) => {
                e.0.push(1);
                e.usize(h.step);
                e.f64(h.times.0);
                e.f64(h.times.1);
                e.f64s(h.start.as_flattened());
            }
        }
        e.usize(c.pairs.len());
        for p in &c.pairs {
            e.usize(p.beside.len());
            e.0.extend(p.beside.iter().map(|b| u8::from(*b)));
        }
        e.0
    }

    /// Reads a file produced by [`RestartFile::encode`].
    pub fn decode(data: &[u8]) -> Result<Self, String> {
        let magic = data.get(..MAGIC.len()).unwrap_or(&[]);
        let previous = magic == MAGIC_05;
        let no_predictor = previous || magic == MAGIC_06;
        let no_beside = no_predictor || magic == MAGIC_07;
        if magic != MAGIC && !no_beside {
            if magic.starts_with(b"CTCRST") {
                return Err(format!(
                    "restart file of format {} (an older ctc): this version reads {}, {}, \
                     {} and {}; run from the start",
                    String::from_utf8_lossy(magic),
                    String::from_utf8_lossy(MAGIC),
                    String::from_utf8_lossy(MAGIC_07),
                    String::from_utf8_lossy(MAGIC_06),
                    String::from_utf8_lossy(MAGIC_05)
                ));
            }
            return Err("not a ctc restart file (bad magic or version)".into());
        }
        let mut d = Dec {
            data,
            pos: MAGIC.len(),
        };
        let dimension = d.usize()?;
        if dimension != D {
            return Err(format!(
                "the restart file was written by a {dimension}D run, this model is {D}D"
            ));
        }
        let fingerprint = d.u64()?;
        let increment = d.usize()?;
        let resume = Resume {
            step: d.usize()?,
            time: d.f64()?,
            dt: d.f64()?,
            easy: d.usize()?,
        };
        let flat = d.f64s()?;
        if flat.len() % D != 0 {
            return Err(
                "restart file corrupted: displacement count not a multiple of the \
                        dimension"
                    .into(),
            );
        }
        let displacement: Vec<[f64; D]> = flat
            .chunks_exact(D)
            .map(|c| std::array::from_fn(|k| c[k]))
            .collect();
        let np = d.len(24)?;
        let mut pairs = Vec::with_capacity(np);
        for _ in 0..np {
            let n = d.len(8)?;
            let entity = (0..n)
                .map(|_| {
                    d.u64().and_then(|v| {
                        if v == u64::MAX {
                            Ok(None)
                        } else {
                            usize::try_from(v)
                                .map(Some)
                                .map_err(|_| "bad entity".into())
                        }
                    })
                })
                .collect::<Result<Vec<_>, String>>()?;
            let multiplier = d.f64s()?;
            let na = d.len(1)?;
            let active = d.bytes(na)?.iter().map(|b| *b != 0).collect();
            let friction = d.f64s()?;
            pairs.push(PairHistory {
                entity,
                multiplier,
                active,
                friction,
                beside: Vec::new(),
            });
        }
        let nc = d.len(8)?;
        let mut points = Vec::with_capacity(nc);
        for _ in 0..nc {
            let n = d.len(POINT_VALUES * 8)?;
            let mut cell = Vec::with_capacity(n);
            for _ in 0..n {
                let mut v = [0.0; POINT_VALUES];
                for x in &mut v {
                    *x = d.f64()?;
                }
                cell.push(MaterialPoint {
                    state: PointState {
                        position: [v[0], v[1], v[2]],
                        volume: v[3],
                        strain: crate::material::Strain::from_column_slice(&v[4..10]),
                        stress: crate::material::Stress::from_column_slice(&v[10..16]),
                    },
                    history: History {
                        ep: v[16],
                        tensor: std::array::from_fn(|k| v[17 + k]),
                    },
                });
            }
            points.push(cell);
        }
        let points_time = d.f64()?;
        let ne = d.len(16)?;
        let mut pvd = Vec::with_capacity(ne);
        for _ in 0..ne {
            let t = d.f64()?;
            pvd.push((t, d.str()?));
        }
        let nk = d.len(16)?;
        let mut couplings = Vec::with_capacity(nk);
        for _ in 0..nk {
            couplings.push((d.usize()?, d.usize()?));
        }
        let dynamics = if previous || d.bytes(1)?[0] == 0 {
            None
        } else {
            let started = d.bytes(1)?[0] != 0;
            let (v, a, r0) = (d.f64s()?, d.f64s()?, d.f64s()?);
            let nf = d.len(8)?;
            let forces0 = (0..nf).map(|_| d.f64s()).collect::<Result<_, _>>()?;
            Some(DynamicState {
                started,
                v,
                a,
                r0,
                forces0,
                kinetic0: d.f64()?,
                energy: d.f64s()?,
            })
        };
        let predictor = if no_predictor || d.bytes(1)?[0] == 0 {
            None
        } else {
            let step = d.usize()?;
            let times = (d.f64()?, d.f64()?);
            let flat = d.f64s()?;
            if flat.len() != displacement.len() * D {
                return Err(
                    "restart file corrupted: the predictor's displacements do not match \
                     the nodes"
                        .into(),
                );
            }
            Some(PredictorHistory {
                step,
                times,
                start: flat
                    .chunks_exact(D)
                    .map(|c| std::array::from_fn(|k| c[k]))
                    .collect(),
            })
        };
        if !no_beside {
            if d.len(8)? != pairs.len() {
                return Err(
                    "restart file corrupted: the beside flags do not match the pairs".into(),
                );
            }
            for p in &mut pairs {
                let n = d.len(1)?;
                p.beside = d.bytes(n)?.iter().map(|b| *b != 0).collect();
            }
        }
        if d.pos != data.len() {
            return Err(format!(
                "restart file corrupted: {} trailing bytes",
                data.len() - d.pos
            ));
        }
        Ok(RestartFile {
            checkpoint: Checkpoint {
                fingerprint,
                increment,
                resume,
                displacement,
                pairs,
                points,
                points_time,
                couplings,
                dynamics,
                predictor,
            },
            pvd,
        })
    }

    /// Reads `path`.
    pub fn read(path: &Path) -> Result<Self, String> {
        let data = std::fs::read(path)
            .map_err(|e| format!("cannot read restart file {}: {e}", path.display()))?;
        Self::decode(&data).map_err(|e| format!("{}: {e}", path.display()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample() -> RestartFile {
        let point = MaterialPoint {
            state: PointState {
                position: [0.25, -1.0 / 3.0, 0.0],
                volume: 1e-300,
                strain: crate::material::Strain::from([
                    1.0,
                    2.0,
                    f64::MIN_POSITIVE,
                    -0.0,
                    0.5,
                    1e-7,
                ]),
                stress: crate::material::Stress::from([0.1, 0.2, 0.3, 0.4, -0.5, 7.0]),
            },
            history: History {
                ep: 0.1 + 0.2,
                tensor: [1.0, 1.0, 1.0, 0.0, 0.0, 0.0],
            },
        };
        RestartFile {
            checkpoint: Checkpoint {
                fingerprint: 0xdead_beef_0123_4567,
                increment: 7,
                resume: Resume {
                    step: 1,
                    time: 0.1 + 0.2,
                    dt: 1.0 / 3.0,
                    easy: 1,
                },
                displacement: vec![[1e-17, -2.5], [std::f64::consts::PI, 0.0]],
                pairs: vec![PairHistory {
                    entity: vec![None, Some(3), Some(0)],
                    multiplier: vec![0.0, 12.5, -1e-9],
                    active: vec![false, true, true],
                    friction: vec![1.0, 0.5, -0.25, 3.0, -1.0, 0.1 + 0.2, 2.0],
                    beside: vec![false, true, false],
                }],
                points: vec![vec![], vec![point; 4]],
                points_time: 0.30000000000000004,
                couplings: vec![(1, 7), (2, 9)],
                dynamics: Some(DynamicState {
                    started: true,
                    v: vec![0.1 + 0.2, -0.0, 1e-300, 4.0],
                    a: vec![1.0 / 3.0, 2.0, -7.5, f64::MIN_POSITIVE],
                    r0: vec![0.5; 4],
                    forces0: vec![vec![1.0; 4], vec![-2.0; 4], vec![0.0; 4], vec![0.5; 4]],
                    kinetic0: 0.005,
                    energy: vec![1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0],
                }),
                predictor: Some(PredictorHistory {
                    step: 1,
                    times: (0.1, 0.1 + 0.2),
                    start: vec![[-1e-17, 2.5], [1.0 / 3.0, -0.0]],
                }),
            },
            pvd: vec![(0.5, "inc_0001.vtu".into()), (1.0, "inc_0002.vtu".into())],
        }
    }

    #[test]
    fn restart_file_round_trip_is_bit_exact() {
        let s = sample();
        let bytes = s.encode();
        let back = RestartFile::decode(&bytes).unwrap();
        assert_eq!(back, s);
        assert_eq!(back.encode(), bytes);
        assert_eq!(
            back.checkpoint.resume.time.to_bits(),
            (0.1f64 + 0.2).to_bits()
        );
    }

    #[test]
    fn a_solid_restart_file_carries_its_dimension() {
        let s = sample();
        let c = &s.checkpoint;
        let solid = RestartFile::<3> {
            checkpoint: Checkpoint {
                fingerprint: c.fingerprint,
                increment: c.increment,
                resume: c.resume,
                displacement: vec![[1e-17, -2.5, 0.1 + 0.2], [0.0, -0.0, 7.0]],
                pairs: Vec::new(),
                points: c.points.clone(),
                points_time: c.points_time,
                couplings: Vec::new(),
                dynamics: None,
                predictor: None,
            },
            pvd: s.pvd.clone(),
        };
        let bytes = solid.encode();
        assert_eq!(RestartFile::<3>::decode(&bytes).unwrap(), solid);
        let e = RestartFile::<2>::decode(&bytes).unwrap_err();
        assert!(e.contains("3D run, this model is 2D"), "{e}");
        let e = RestartFile::<3>::decode(&s.encode()).unwrap_err();
        assert!(e.contains("2D run"), "{e}");
    }

    /// Bytes of the beside section at the end of a file (format 08): a
    /// count of pairs, then per pair a count and one byte per slave node.
    fn beside_section_len(s: &RestartFile<2>) -> usize {
        let pairs = &s.checkpoint.pairs;
        8 * (1 + pairs.len()) + pairs.iter().map(|p| p.beside.len()).sum::<usize>()
    }

    #[test]
    fn previous_format_files_are_read_without_dynamic_state_and_older_ones_refused() {
        // the format 07: its magic, no beside flags at the end (a count of
        // pairs, then per pair a count and its bytes): read with none
        let mut s = sample();
        let mut bytes = s.encode();
        let tail = beside_section_len(&s);
        bytes.truncate(bytes.len() - tail);
        bytes[..8].copy_from_slice(MAGIC_07);
        s.checkpoint.pairs.iter_mut().for_each(|p| p.beside.clear());
        assert_eq!(RestartFile::<2>::decode(&bytes).unwrap(), s);
        s.checkpoint.predictor = None;
        let mut bytes = s.encode();
        // the format 06: its magic, no predictor flag, no beside flags
        bytes.truncate(bytes.len() - 8 * (1 + s.checkpoint.pairs.len()));
        bytes[..8].copy_from_slice(MAGIC_06);
        bytes.pop();
        assert_eq!(RestartFile::<2>::decode(&bytes).unwrap(), s);
        s.checkpoint.dynamics = None;
        let mut bytes = s.encode();
        // the format 05: its magic, no dynamic and no predictor flag
        bytes.truncate(bytes.len() - 8 * (1 + s.checkpoint.pairs.len()));
        bytes[..8].copy_from_slice(MAGIC_05);
        bytes.pop();
        bytes.pop();
        assert_eq!(RestartFile::<2>::decode(&bytes).unwrap(), s);
        bytes[..8].copy_from_slice(b"CTCRST04");
        let e = RestartFile::<2>::decode(&bytes).unwrap_err();
        assert!(
            e.contains("format CTCRST04") && e.contains("run from the start"),
            "{e}"
        );
    }

    #[test]
    fn beside_flags_that_do_not_match_the_pairs_are_an_error() {
        // a file whose beside section counts another number of pairs
        let s = sample();
        let mut bytes = s.encode();
        let tail = beside_section_len(&s);
        let at = bytes.len() - tail;
        bytes[at..at + 8].copy_from_slice(&0u64.to_le_bytes());
        let e = RestartFile::<2>::decode(&bytes).unwrap_err();
        assert!(e.contains("beside flags do not match"), "{e}");
    }

    #[test]
    fn truncated_or_foreign_restart_files_are_errors_not_panics() {
        let bytes = sample().encode();
        for n in 0..bytes.len() {
            assert!(RestartFile::<2>::decode(&bytes[..n]).is_err(), "prefix {n}");
        }
        let mut extra = bytes.clone();
        extra.push(0);
        assert!(RestartFile::<2>::decode(&extra).is_err());
        let mut bad = bytes;
        bad[0] = b'X';
        assert!(RestartFile::<2>::decode(&bad)
            .unwrap_err()
            .contains("magic"));
    }
}
