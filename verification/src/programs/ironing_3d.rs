//! `ironing_3d` — the 3D ironing comparison of issue 18: the die-on-slab
//! of M. A. Puso, T. A. Laursen, "A mortar segment-to-segment frictional
//! contact method for large deformations", CMAME 193 (2004) 4891-4913
//! (their ironing example), run with every contact discretization the
//! engine has for it, tags `3d`, `contact`, `friction`, `ironing`,
//! `deformable`.
//!
//! A Neo-Hookean slab `9 x 3 x 4` (x: sliding, y: thickness, z: width;
//! E = 1, nu = 0.3, bottom fixed) under a cylindrical-cap die of radius 3
//! and width 5.2 (annular sector `2 <= r <= 3`, 200..340 degrees, 5 degree
//! facets, extruded along z; E = 1000, nu = 0.499), axis at `x = 2`, its
//! lowest line touching the slab's top. The die's top is pressed down 1.4
//! (`t` 0..1), then slid 4.0 along x (`t` 1..2); area penalty 500, slave
//! the slab's top, master the die's curved face, finite strain. The same
//! deck as `examples/ironing_3d.ctc`, with the contact block of each
//! variant (the rows of the comparison table of issue 18):
//!
//! | variant | formulation | smoothing | mu |
//! |---|---|---|---|
//! | `ntf faceted mu 0` | node-to-facet | none | 0 |
//! | `ntf nagata mu 0` | node-to-facet | Nagata patches | 0 |
//! | `mortar mu 0` | mortar | - | 0 |
//! | `ntf faceted mu 0.3` | node-to-facet | none | 0.3 |
//! | `mortar mu 0.3` | mortar | - | 0.3 |
//! | `ntf nagata mu 0.3` | node-to-facet | Nagata patches | 0.3 |
//!
//! (friction on Nagata patches: `ctc_engine::contact::friction_nagata`;
//! that row also reports the largest `|T . n| / |T|` over the slab nodes,
//! `n` the normal each node reports, the patch's: the friction acts in the
//! tangent plane of the normal that gives the gap). Each run reports the die force histories `F_n`
//! (the slab's contact force along -y) and `F_t` (along +x), drawn on one
//! figure of the report (`ironing_3d_forces.svg`) with the Newton
//! iterations of every increment (`ironing_3d_iterations.svg`); and the
//! figures of the table: the end time reached, the `F_n` oscillation
//! `(max - min) / mean` over the second half of the slide (`t >= 1.5`),
//! with friction the mean `F_t / F_n` over the slide past its start-up
//! (`t > 1.25`), without friction `(max - min)` of `F_t` over the mean
//! `F_n`, the Newton iterations per slide increment, increments and
//! cutbacks, and the balance of the contact force against the die's
//! reaction.
//!
//! What has a reference:
//! - `F_t / F_n -> mu` in steady sliding (Coulomb: every slipping node
//!   carries `|T| = mu R_N`; the resultants differ by the ploughing of the
//!   die through the slab's bulge and by the nodes still sticking, so the
//!   error against mu is guarded at its measured value). Puso & Laursen's
//!   figure plots the force histories; no numbers of it were found to
//!   state here (searched: the paper's text is not among the stored
//!   pages), so mu itself is the reference.
//! - Smoothing and mortar against the faceted die: the ratios of their
//!   `F_n` oscillation to the faceted node-to-facet one (below 1 is the
//!   point of smoothing).
//! - Equilibrium: the contact force against the die's reaction.
//! - Every run reaching the end (`t = 2`).
//!
//! Levels: level 0 (the default, in the catalogue of every CI run) is the
//! coarse short deck of `ironing_nagata_3d` (slab `6 x 3 x 2` cells, die
//! 28 x 3, press 0.5 in 3 increments, slide 1.0 in 8) with two variants,
//! node-to-facet faceted and Nagata at mu = 0.3 (its frictionless faceted and Nagata
//! runs are `ironing_nagata_3d`'s level 0; a mortar run costs 19 s (mu
//! 0) and 45 s (mu 0.3) of CPU in debug there since the load-stiffness
//! cap below, 67 s and 74 s before: measured by `ctc run -v` of the
//! generated decks, still too much for the catalogue); level 1 (`ctc verify ironing_3d
//! --max-level 1`) is the benchmark (slab `9 x 3 x 4`, die 28 x 5, press
//! 1.4 in 7, slide 4.0 in 20) with the five variants.
//!
//! The mortar mu = 0.3 press cycle (its contact set 15 <-> 11 at the
//! second press increment of the benchmark, 9 <-> 3 at level 0's) was the
//! stick point of the nodes closing in the increment under the die's
//! flank: their committed position, so the relative motion of the two
//! surfaces before they touched counted as slip (a trial force `alpha_T
//! |s|`, `|s|` about 0.014 at level 0's press), and they slipped where the
//! converged state has them sticking with a third of the middle node's
//! pressure (0.064 vs 0.209, gap -1.3e-4): from the slipping state Newton opened them
//! (gap +8e-5), from the open one it drove them 0.1 into the die (the slab
//! is 500 times softer than the area penalty) and the line search halved
//! down to 1/64. Measured by a trace of every node's status per
//! evaluation (`ctc run -v` of level 0's mortar mu = 0.3 deck). Such a
//! node now sticks where its path crossed the master
//! (`friction3d::Law::impact`, `a = tau s`, `tau = g0 / (g0 - g)`): its
//! tangential force vanishes with its gap. Level-0 deck, `ctc run`
//! (debug): that increment 30 iterations and a cutback -> 7; the run 203
//! -> 147 Newton iterations (18 -> 17 increments, 10.8 -> 8.1 per slide
//! increment), `F_t / F_n` 0.2875 -> 0.2876, `F_n` oscillation 0.049 ->
//! 0.050; its 3 cutbacks are now in the slide (t 1.62, and twice at
//! 1.81; not traced: the frictionless mortar press also cuts back twice in
//! the same press increment at level 0, the open/closed kink of a slab
//! 500 times softer than its penalty).
//!
//! The frictionless mortar cutbacks at level 0 (press and slide) were
//! the load stiffness of overshooting iterates, not the active set:
//! traced per slave row and evaluation (`CTC_LOG=debug ctc run -v` of
//! level 0's mortar mu = 0 deck, which now prints every row), the first
//! step of a press increment closes the nodes that were open at its start
//! 0.1 deep (the slab is 500 times softer than the penalty: 50 times
//! their equilibrium depth, `R` 24..64 instead of ~0.5); at that pressure
//! the rows' load-stiffness term `p dB/dx` (about `p h`, against the
//! slab's `E h`) dominates the tangent, and the next steps moved slab
//! nodes up to 5 along the surface and 1.2 into the die (line search down
//! to 1/1024, 20 + 5 iterations and two cutbacks in the second press
//! increment). No partly covered facet or negative dual area on the
//! switching nodes (those are fully covered). The tangent now takes that
//! term with the pressure capped at twice the pair's largest committed
//! pressure (`mortar::LOAD_STIFFNESS_CAP`; exact below it). Measured
//! (`ctc run -v` of the generated decks, dev profile, CPU s of
//! `/usr/bin/time` on a loaded machine; before = the same commit without
//! the cap; mu = 0.3's remaining cutback not traced):
//!
//! | deck | increments | iterations | cutbacks | CPU s | `F_n` osc. | `F_t/F_n` |
//! |---|---|---|---|---|---|---|
//! | level 0, mu 0, before | 20 | 146 | 4 | 67.0 | 0.076 | - |
//! | level 0, mu 0, after | 11 | 57 | 0 | 19.2 | 0.076 | - |
//! | level 0, mu 0.3, before | 17 | 147 | 3 | 73.5 | 0.050 | 0.2876 |
//! | level 0, mu 0.3, after | 13 | 103 | 1 (t 1.75) | 44.7 | 0.048 | 0.2870 |
//!
//! Level 1 (the benchmark's decks, after; not run to the end in the
//! session): the press in its 7 increments without cutback, mu 0 45
//! iterations (6 5 4 5 5 8 12), mu 0.3 39; mu 0.3 then slid to t = 1.35
//! (increments of 9 5 5 8 6 13 16 18 iterations, one cutback at t = 1.3).
//! The frictionless slide failed its first increment (30 iterations,
//! cut back, then again): a second cause, traced at level 0 (every
//! frictionless slide increment, before and after the cap): the
//! prescribed first step of a slide increment
//! leaves every closed node open by 0.0015..0.0019 (the linear model's
//! error over the 0.125 slide exceeds the equilibrium penetration
//! `p / alpha` ~ 5e-4), all forces vanish (residual 0.58), and the next
//! step from the all-open state puts them 0.28..0.49 into the die (line
//! search to 1/64). Level 0 recovered in 5 iterations per increment, the
//! benchmark's 0.2 slide steps (nodes open by 0.004..0.0085) did not.
//! Fixed by the hold (`mortar::HOLD_BAND`, frictionless rows): a node
//! closed at the last accepted iterate and open within `5e-2 sqrt(T)`
//! keeps the closed branch of the penalty law (tensile) for one iterate,
//! and the step from there lands at the penetration (level 0: slide
//! increments 5 -> 4 iterations, `ctc run -v`). Keeping only the penalty
//! tangent with no force (the closed-gap start's `touching` rule) did not
//! help: the step from it stays at the open gap. The first-contact
//! round-off rule of `mortar::LOAD_STIFFNESS_CAP` with it (`ctc run -v`
//! of the generated decks, debug, CPU s; before = the cap of the table
//! above):
//!
//! | deck | increments | iterations | cutbacks | CPU s | `F_n` osc. |
//! |---|---|---|---|---|---|
//! | level 0, mu 0, before | 11 | 57 | 0 | 25.3 | 0.0765 |
//! | level 0, mu 0, after | 11 | 49 | 0 | 12.6 | 0.0765 |
//! | level 1, mu 0, before | fails its first slide increment | | | | |
//! | level 1, mu 0, after | 32 | 201 | 3 | 153.4 | 0.0371 |
//!
//! (level 0: `F_n` at t = 1 1.10955212 both, balance 1.1e-8 -> 5.0e-10;
//! level 1 after: the press 7 increments / 35 iterations (45 before), the
//! slide to t = 2 in 25 increments / 151 iterations (+ 15 in the three
//! cut-back attempts), cutbacks at t 1.25,
//! 1.40, 1.95 (residual growth, not traced), `F_t` spread 0.052 of the
//! mean `F_n`, balance 1.0e-7. Level 0 mu 0.3 unchanged: 13 / 103 / 1,
//! `F_n` oscillation 0.0481, `F_t / F_n` 0.2870: the frictional rows hold
//! nothing.) The figures of `ctc verify ironing_3d --max-level 1
//! --report DIR` (the `mortar mu 0` row, `ironing_3d_forces.svg`,
//! `ironing_3d_iterations.svg`) come from this run; not regenerated here.
//!
//! `F_n` at the end of the press unchanged (level 0 mu 0: 1.10955211 both,
//! to 1e-8); dropping the term altogether (an experiment) also ran level 0
//! mu 0 without cutback, but in 99 iterations (linear convergence).
//!
//! Node-to-facet faceted mu = 0.3 cycles at level 0's third press
//! increment (9 <-> 7 contacts: 30 iterations twice, cut back to a
//! quarter), traced per node and evaluation (`ctc run -v` of level 0's
//! deck, a temporary print in `friction_facet::apply`). Not a first
//! touch: no node touches for the first time in that increment. The two
//! flank nodes that switch (slab x = 3, z = 1.6 and x = 1, z = 2.6) hold
//! stick points from increment 2, where they closed barely (`R_N` 0.05,
//! 0.02); the converged answer (at a quarter of the increment) has them
//! sticking, carried down with the die (`|T|` 0.015, 0.008 within cones
//! of 0.023, 0.010). The predictor leaves them open, the Newton step of
//! an open node puts it 0.19 into the die (the slab is 500 times softer
//! than the penalty), the line search cuts to 1/64, where they are closed
//! shallow (gap -6e-4..-3e-3) but 0.05..0.07 from their stick point:
//! slipping (trial 1.1..2.9 against `mu R_N` 0.05..0.45), a state whose
//! tangent holds them nowhere along the flank, and the next full step
//! opens them again: an open / closed and stick / slip globalization issue
//! at small normal forces. Now the penalty cycling guard of node-to-facet
//! (`node_to_facet::DeformablePair::held`) sees the contact set come back
//! (7 -> 9 -> 7 at the third iterate) and freezes the two nodes closed
//! and sticking (nodes that slipped in the cycle keep the law's
//! friction); the press converges in its 3 increments, with the frozen
//! nodes closed and inside their cones (consistent): level 0 180 -> 119
//! Newton iterations (press 98 -> 29), 17 -> 14 increments, 3 -> 1
//! cutbacks (the one left in the slide, whose 11 increments take 82 ->
//! 90 iterations), `F_t / F_n` 0.3024 unchanged, `F_n` oscillation 0.079
//! unchanged (`ctc verify ironing_3d`, debug; freezing every cycling node
//! sticking gave 86 iterations and no cutback here but cost the benchmark
//! deck, see `docs/ARCHITECTURE.md`). In increment 2 the same nodes did close
//! for the first time, but the die moving onto them leaves their
//! converged position behind the facet's *current* plane (`g_0 <= 0`), so
//! they take the foot of `x_0` on the facet at the first closed iterate
//! (convected from then on), not the crossing rule: that point depends on
//! the iterate (first closed gap -0.08, converged -1.1e-4: the stick
//! point 0.013 off, and they converged slipping, trial 0.67 against `mu
//! R_N` 0.016). The crossing rule now follows the iterate (`friction_facet`,
//! penalty, as mortar's), which leaves level 0's figures bit-for-bit
//! unchanged (`ctc verify ironing_3d`: 180 iterations, 17 increments) and
//! moves the benchmark deck's (`ctc verify ironing_ntf_3d`, debug: 364 ->
//! 352 iterations, 32 -> 34 increments, 3 cutbacks, `F_n` oscillation
//! 0.134 -> 0.091, `F_t / F_n` 0.396 -> 0.391, `F_t` oscillation 0.133 ->
//! 0.146);
//! taking the spatial `x_0` for the nodes behind the plane instead gave
//! level 0 180 -> 167 iterations and 3 -> 2 cutbacks (the press cycle
//! unchanged) but stopped `friction_blocks_ntf_3d` in its press (its block
//! overlaps the base: the master's own motion counted as slip). The fix
//! for those nodes is the path relative to the facet (the facet's committed
//! node positions, which `DeformablePair` keeps for mortar friction only).
//!
//! ```text
//!            die top: u_y = -1.4, then u_x = 4
//!          .-''''''-.   die, R = 3 (cap 200..340 deg), E = 1000
//!         /          \
//!   +-----\----------/------------------+  slab top (slave), mu = 0 / 0.3
//!   |      '--------'    slab 9 x 3 x 4, Neo-Hooke E = 1, nu = 0.3
//!   +-----------------------------------+  fixed
//! ```
//!
//! ## Which normal force is right: mortar ~7 % above node-to-facet
//!
//! The second case of this file, `ironing_plane_strain_3d`, answers it
//! on the benchmark's section: the slab held by `u_z = 0` on both z
//! faces is plane strain, the reference is ctc's 2D plane-strain run of
//! the same section (the same cells along x and y, the same 28 die
//! facets, [`deck_2d`]) with node-to-segment and 2D mortar. `F_n` per
//! unit width at the end of the press (`t = 1`, press 1.4, area penalty
//! 500; `ctc run` release `--threads 1` of the decks of [`Setup`]):
//!
//! | slab cell | 2D mortar | 2D node-to-segment | mortar / nts - 1 |
//! |---|---|---|---|
//! | 1 (benchmark) | 2.8575 | 2.6170 | +9.2 % |
//! | 1/2 | 2.7482 | 2.7035 | +1.7 % |
//! | 1/4 | 2.7157 | 2.7080 | +0.28 % |
//!
//! Mortar converges from above (differences 0.109, 0.033: rate h^1.7),
//! node-to-segment from below (0.087, 0.005), both to ~2.71: neither is
//! wrong, mortar is the coarser one on this mesh (a slab cell of 1 under a
//! contact zone ~5.6 wide: 5 or 6 nodes in contact; the weighted gap
//! averages the gap over each node's support, and the chords of the slab's
//! surface under the convex die lie inside the circle the nodes sit on,
//! so the nodes go deeper than node-to-segment's). Penalty x10 (5000)
//! moves `F_n` by +0.2 % (2D node-to-segment 2.6223 at cell 1, mortar
//! 2.7525 at 1/2, 2.7198 at 1/4; many x10 runs stop in the slide or the
//! press on contact chatter), the die's faceting halved (56 facets) by
//! < 0.2 % (2.6154, 2.8629 at cell 1): the cell size is the whole
//! difference.
//! The 3D slab in plane strain reproduces the 2D runs: mortar 2.8575 =
//! 2D to 1e-5 (the die's deformation), node-to-facet 2.5905 (-1.0 %:
//! the slab node under the die's lowest vertex, `x = 2`, takes the other
//! of its two facets at first touch, tie of equal gaps, and is pushed
//! the other way along x; with the die's axis at `x = 2.25` 3D and 2D
//! agree to 9e-5, 2.66819 / 2.66842). In the slide the same ordering
//! holds and converges the same way (mean `F_n` over `t >= 1.5`, cells
//! 1, 1/2, 1/4: 2D mortar 3.079, 3.032, 2.999; 3D plane-strain
//! node-to-facet 2.835, 2.965, 2.987; 3D mortar 3.122 at cell 1, to t =
//! 1.955). The benchmark's free slab (no `u_z` condition), cell 1, `t =
//! 1`: node-to-facet 2.4066 per unit width, Nagata 2.4151, mortar 2.5981
//! (+8.0 %; mean slide 2.609 / 2.629 / -; node-to-facet at cell 1/2,
//! 8 cells across z: 2.4604, +2.2 %, mean slide 2.679): the ~7 % of
//! mortar over node-to-facet there is this coarse-mesh difference.
//!
//! The 2D node-to-segment slide at cells 1/2 and 1/4 lost slab nodes
//! under the die (`F_n` 2.74 -> 2.47 at t = 1.1, 2.74 -> 2.30 at 1.5,
//! 2.44 -> 0.97 at 1.65 at cell 1/2; slide means over `t >= 1.5` 1.70 and
//! 2.83): at cell 1/2 the predictor of the second slide increment
//! started slab node 120 (x = 3) open (gap +5.7e-4), the Newton step
//! with it free put it 0.54 inside the die, past the depth window
//! `max(prof, L) = 0.5` of `node_to_segment`, so it lost its segment and
//! the converged state had it inside the die (`CTC_LOG=debug ctc run
//! -v`). A node now keeps, at any depth, the segments of its memory (the
//! last segment, its neighbours and the walk from it towards the foot:
//! `node_to_segment::memory_walk`). After: the 2D slide follows the 3D
//! plane-strain node-to-facet run at cell 1/2 to 8e-6 at 16 of its 20
//! slide times (5e-4..4.5e-3 at the other 4), slide mean 2.965 (3D
//! 2.964), minimum 2.740 (3D 2.740). The case's level `l` runs that 2D
//! slide at cells `1 / 2^(l + 1)` against 2D mortar's (the two converge
//! together: slide means 3.032 / 2.999 for mortar at 1/2, 1/4) and its
//! minimum `F_n` against the press's end.
//!
//! ## The lateral force `F_z` of the benchmark deck at mu = 0.3 (traced)
//!
//! The benchmark deck (`examples/ironing_3d.ctc`, `ironing_ntf_3d`'s
//! level 0, this program's level-1 `ntf faceted mu 0.3` row) is symmetric
//! about the slab's mid-width plane `z = 2.6` (slab `z` 0.6..4.6 in 4
//! cells, die 0..5.2 in 5 layers; the mirror takes the slab's top-node row
//! `j` to `4 - j`, die facet `(layer l, arc a)` to `(4 - l, a)`), so `F_z`
//! is round-off. With the memory rule (ff1057d) it was 1e-3..6e-3 from `t
//! = 1.6` (before it, up to 4.6e-7: already above round-off). Traced
//! (`CTC_LOG=debug ctc run -v --threads 1` of the example, every closed
//! node's `node:facet:gap` per evaluation compared with its mirror's): the
//! converged states of slide increments 1..18 are mirror images (facets
//! mirrored, gaps equal to the log's 4 digits, `F_z` <= 2.8e-8); the
//! first iterate of increment 19 is not (node 75 closed at -8.2e-4 on
//! facet 50, its mirror 155 open), and the increment converged with
//! mirror nodes 0.13 apart (74 / 154), three of them on facets one arc
//! apart (32 / 192 on facets 8 / 119, 33 / 193 on 13 / 124, 74 / 154 on
//! 46 / 101), `F_z` 6.0e-3, then 1.3e-3..1.6e-3 to the end. Not the
//! search: up to the diverging iterate no node was matched off its
//! mirror's facet, and no memory facet was kept past a closer one. The
//! cause was the tangent of the increment's first step: a node that
//! slipped in increment 18 starts increment 19 from the stick point the
//! return map left, so its trial force lies on the cone `mu R_N` to
//! round-off and `|t*| <= mu R_N` chose stick (tangent `k_T` along the
//! surface) or slip (none) by the last bits; mirror nodes got different
//! tangents, the first steps differed, and the path-dependent answer
//! (first-touch stick points, the seam rule) kept the difference. A trial
//! within [`ctc_engine::contact::friction_facet::CONE_TIE`] (1e-9) below
//! the cone now slips (test
//! `a_node_that_slipped_starts_the_next_increment_slipping_whatever_the_round_off`).
//! Measured (`ctc run --threads 1` of the example deck, debug; `ctc
//! verify NAME --max-level 0 -j 1 --json`):
//!
//! | run | before | after |
//! |---|---|---|
//! | example: increments / its / cutbacks | 28 / 339 / 1 | 27 / 266 / 0 |
//! | example: largest `|F_z|` | 6.0e-3 | 1.9e-13 |
//! | `ironing_ntf_3d`: `F_n` oscillation | 0.136 | 0.0913 |
//! | `ironing_ntf_3d`: `F_t / F_n`, `F_t` oscillation | 0.3930, 0.132 | 0.3898, 0.132 |
//! | `ironing_3d` level 0: increments / its / cutbacks | 14 / 119 / 1 | 16 / 134 / 3 |
//! | `ironing_3d` level 0: `F_t / F_n`, its per slide increment | 0.3024, 8.18 | 0.2998, 5.80 |
//! | `friction_blocks_ntf_3d`: its | 751 | 683 |
//!
//! (`ironing_ntf_3d`'s `F_n` oscillation is back to its 0.093 before the
//! memory rule: the 0.136 was the asymmetric path. `ironing_3d` level 0
//! now cuts back twice in its third press increment, the press cycle of
//! the cycling guard above; its slide is cheaper.) The other tie rule
//! (a trial on the cone to round-off sticks) is as deterministic but
//! slower where nodes keep sliding: example 39 / 486 / 3, blocks 766,
//! `ironing_3d` level 0 11 / 101 / 0.
//!
//! ## Friction on Nagata patches (issue 18): with and without smoothing
//!
//! The `ntf nagata mu 0.3` row against `ntf faceted mu 0.3`, the same deck
//! (`ctc run --threads 1` of the generated decks, debug binary, CPU user
//! s; the figures by [`run_variant`]'s definitions from `history.csv` and
//! `summary.json`, level 0 also by `ctc verify ironing_3d -j 1`):
//!
//! | deck | incr / its / cutbacks | `F_n` osc. | `F_t` spread / mean `F_n` | `F_t / F_n` | its / slide incr. | balance | CPU s |
//! |---|---|---|---|---|---|---|---|
//! | level 0, faceted | 11 / 88 / 0 | 0.0749 | 0.0536 | 0.3050 | 6.75 | 3.7e-10 | 0.8 |
//! | level 0, Nagata | 11 / 89 / 0 | 0.0695 | 0.0286 | 0.2938 | 8.50 | 4.1e-9 | 1.8 |
//! | level 1, faceted | 27 / 229 / 0 | 0.0886 | 0.0472 | 0.3893 | 8.85 | 5.1e-9 | 4.5 |
//! | level 1, Nagata | 32 / 317 / 2 | 0.0872 | 0.0500 | 0.3670 | 8.36 | - | 16.7 |
//! | before: level 0, faceted | 16 / 134 / 3 | 0.0793 | 0.0537 | 0.2998 | 5.80 | 1.0e-8 | 1.4 |
//! | before: level 0, Nagata | 19 / 228 / 3 | 0.0700 | 0.0308 | 0.2940 | 9.29 | 2.9e-8 | 6.2 |
//! | before: level 1, faceted | 27 / 266 / 0 | 0.0913 | 0.0523 | 0.3898 | 10.45 | 3.9e-9 | 6.8 |
//! | before: level 1, Nagata | 60 / 716 / 11 | 0.0870 | 0.0506 | 0.3680 | 8.83 | 1.5e-8 | 61.2 |
//!
//! ("before": without the hold of frictional nodes below; the balance of
//! level 1 faceted is `ctc verify ironing_ntf_3d`'s, the same deck; level
//! 1 Nagata's was not rerun, `ctc run` writes no die reaction.)
//! Oscillation ratios Nagata / faceted: `F_n` 0.927 (level 0), 0.984
//! (level 1); `F_t` spread 0.533, 1.059 (before 0.884, 0.953; 0.574,
//! 0.967: the faceted run's `F_t` spread fell more, 0.0523 -> 0.0472,
//! than Nagata's). `F_t / F_n` of the benchmark comes 0.022 closer to mu
//! on the patches (the ploughing term of the section below: the patch's
//! normal turns smoothly under the slab nodes). Largest `|F_z|` 1.1e-13
//! / 1.7e-13 (Nagata, levels 0 / 1; the mirror symmetry kept), `|T . n|
//! / |T|` 5.5e-16 at level 0.
//!
//! The iterations: traced at level 0 (`ctc run -v`), the first step of a
//! slide increment left every closed node open (`contacts 0`, the
//! prescribed die step through the committed tangent) and the next steps
//! needed the line search (down to 1/64) before the quadratic rate set in
//! (`1e-3 -> 1e-5 -> 1e-7 -> 1e-11`): a globalization issue of the
//! frictional pair, not the tangent (whose finite-difference check is
//! `friction_nagata::tests`). The node-to-facet hold
//! (`mortar::HOLD_BAND`: a node that carried a normal force at the last
//! accepted iterate and is open within the band keeps the closed branch
//! for that iterate) was for frictionless pairs only; it now keeps
//! frictional nodes too in quasi-static steps
//! (`node_to_facet::DeformablePair::hold_friction`), a held node's
//! friction the law's in the cone of the constant `mu R_N^acc`, `R_N^acc`
//! the normal force it carried at the last accepted iterate (test
//! `a_held_node_s_friction_takes_the_cone_of_its_last_normal_force_and_its_tangent_is_exact`,
//! FD error <= 1.7e-9). Held with no friction instead (the stick point
//! kept, or the law at the tensile force, which the cone clips to 0: the
//! same iterates) it was worse: level 0 Nagata 22 / 310 / 4, faceted 12
//! / 97 / 1; level 1 Nagata 92 / 1306 / 15, faceted 34 / 375 / 3. The
//! benchmark's Nagata run keeps 2 cutbacks (before: 2 in the press, the
//! increments from t = 0.14 and 0.64, 9 in the slide). The press one (t =
//! 0.29 -> 0.43, residual 7.2e-6 at iteration 30), traced (`CTC_LOG=debug
//! ctc run -v`
//! of the level-1 Nagata deck, closed nodes per evaluation): the row of
//! slab nodes at the die's flank (33, 73, 113, 153, 193: one x, every z)
//! cycles closed (gap -3e-4..-4e-4) -> held (open by 5e-5..5e-4, within
//! the band) -> open (no longer held: the hold lasts one iterate) -> 4e-3
//! into the die after the next step (line search to 1/64, residual
//! 0.3..0.5) -> closed; a three-iterate cycle, which the cycling guard
//! (`A -> B -> A` of the status set) catches once (iteration 12, 2
//! nodes) while the row's other nodes keep cycling; the increment
//! converges from iteration 25 on (`4.7e-2 -> 7.2e-6`), too late. Not
//! fixed: a hold of such a node past one iterate, or the guard counting a
//! held iterate as closed, are the candidates (not measured). The slide's
//! cutback (t = 1.60 -> 1.65) not traced.
//!
//! ## `F_t / F_n` at mu = 0.3: node-to-facet vs mortar (traced)
//!
//! The 0.393 (node-to-facet) against 0.287 (mortar) of the last closing
//! note compared two decks: 0.393 is the benchmark's (press 1.4), 0.287
//! level 0's (press 0.5). On one deck the two differ by 4 % (level 0)
//! and 15 % (the benchmark). The split, per converged increment from the
//! contact CSVs (`ctc run --threads 1`, debug; per closed slab node the
//! `force` minus its `tangential` part is the normal force `N`; `F_x =
//! sum N_x + sum T_x`, `F_n = -(sum N_y + sum T_y)`; means over `t >
//! 1.25` of the per-increment ratios, as [`run_variant`]'s `F_t / F_n`):
//!
//! | deck | slab cells | `F_t / F_n` | normal part `N_x / F_n` | friction part `T_x / F_n` |
//! |---|---|---|---|---|
//! | level 0, node-to-facet | 6 x 3 x 2 | 0.2998 | +0.0007 | 0.2991 |
//! | level 0, mortar | 6 x 3 x 2 | 0.2870 | -0.0135 | 0.3005 |
//! | level 0, node-to-facet | 12 x 6 x 4 | 0.2874 | -0.0089 | 0.2963 |
//! | level 0, mortar | 12 x 6 x 4 | 0.2854 | -0.0128 | 0.2982 |
//! | benchmark, node-to-facet | 9 x 3 x 4 | 0.3898 | +0.0858 | 0.3040 |
//! | benchmark, mortar | 9 x 3 x 4 | 0.3394 | +0.0343 | 0.3051 |
//! | benchmark, node-to-facet | 18 x 6 x 8 | 0.3598 | +0.0578 | 0.3020 |
//!
//! - The friction parts agree (to 1 %), the difference is all in the
//!   normal forces' x-component (the ploughing). Coulomb holds node by
//!   node in both: node-to-facet's slipping nodes carry `|T| = mu |N|`
//!   to 7e-16; a mortar node carries `|T| = mu R_N A_j / T_j` and `|N| =
//!   R_N |sum_e D_jj n_e| / T_j`, so `|T| / (mu |N|) = A_j / |sum_e D_jj
//!   n_e| >= 1` (the facet normals of the node's support turn: 1 + 1.4e-2
//!   at most on level 0's slab, 5e-3 on the refined one), the same
//!   pressure integrated over the support, its normals summed.
//! - The normal: node-to-facet takes the master's (the die's facet, or its
//!   edge's), mortar the slave's (the slab's nodal normal, `-sum_e D_jj
//!   n_e`); each takes one normal for its gap, its normal force and its
//!   friction's tangent plane. Under a convex die the slab's 1-cell
//!   facets are chords, so the two normals differ by up to half a chord's
//!   angle and the normal forces' x-parts differ with them.
//! - Which is right: refining the slab (cells halved; die unchanged)
//!   moves node-to-facet onto mortar (level 0: 0.2998 -> 0.2874, mortar
//!   0.2870 -> 0.2854; the normal part +0.0007 -> -0.0089 against
//!   mortar's -0.0135 -> -0.0128), and on the benchmark node-to-facet
//!   goes 0.3898 -> 0.3598 (its normal part 0.086 -> 0.058, against
//!   mortar's 0.034 on the coarse slab; the refined run: 41 increments,
//!   621 iterations, 5 cutbacks, 116 s CPU; `ironing_ntf_3d` level 1,
//!   with the die's facets halved too, gave 0.354 before the memory
//!   rule; mortar on the refined benchmark slab was not run, ~8x its
//!   191 s). Mortar, whose weighted gap and normal
//!   average over each node's support, moves least: on these coarse
//!   slabs it is the closer one, and node-to-facet's excess over it is
//!   its discretization error, which the refinement shrinks (level 0:
//!   0.0128 -> 0.0020). Not a defect.
//! - Against mu: the friction part is mu (0.296..0.305), the normal part
//!   is the die's ploughing: negative at the shallow press (the slab
//!   carries more pressure behind the die's axis), +3.4 % of `F_n` for
//!   mortar at the benchmark's 1.4. `F_t / F_n` of the benchmark is mu
//!   plus 0.034..0.086 of ploughing; mortar's 0.34 is the better figure.
//!
//! ## The level-1 table on the search with memory (issue 18)
//!
//! `CTC_THREADS=1 ctc verify ironing_3d --max-level 1 -j 1 --json
//! --report DIR` (debug binary with the engine at -O2, after the
//! memory rule, the `prof` window and the tie rule of
//! `friction_facet::CONE_TIE`; 246.7 s user
//! CPU for levels 0 and 1, load 7-9); per variant the increments /
//! iterations / cutbacks of `ctc run --threads 1` of the same deck
//! (`history.csv`, `summary.json`; mortar mu 0's is the level's total
//! less the other four's, 1240 now, 1313 before the tie rule); last
//! session's figures (before the memory rule) in the last column:
//!
//! | variant | incr / its / cutbacks | `F_n` osc. | `F_t / F_n` (mu 0.3) or `F_t` spread (mu 0) | its / slide incr. | end | before |
//! |---|---|---|---|---|---|---|
//! | ntf faceted mu 0 | 27 / 170 / 0 | 0.0323 | 0.0525 | 6.80 | 2 | 31 / 245 / 2 |
//! | ntf nagata mu 0 | 27 / 161 / 0 | 0.0255 | 0.0471 | 5.95 | 2 | 27 / 161 / 0 |
//! | mortar mu 0 | 32 / 201 / 3 | 0.0371 | 0.0190 | 6.04 | 2 | 32 / 201 / 3 |
//! | ntf faceted mu 0.3 | 27 / 266 / 0 | 0.0913 | 0.3898 | 10.45 | 2 | 30 / 315 / 2 |
//! | mortar mu 0.3 | 37 / 442 / 4 | 0.0655 | 0.3394 | 11.77 | 2 | 37 / 442 / 4 |
//!
//! Oscillation ratios: Nagata / faceted 0.790, mortar / faceted 1.148 (mu
//! 0) and 0.718 (mu 0.3). Balance contact force vs die reaction 3e-10..
//! 8e-9. The mortar rows and Nagata's counts did not move (mortar keeps
//! its window for every pair); the faceted
//! frictionless run lost its two cutbacks with the memory rule, the
//! faceted mu = 0.3 run is the benchmark deck of `ironing_ntf_3d` (its
//! 28 / 339 / 1, `F_n` oscillation 0.136, with the memory rule before the
//! tie rule; 0.393 then). Every variant reaches `t = 2`, with 7
//! cutbacks in all (mortar's), where last session's had 11. CPU per run
//! (`ctc run`, debug, niced under load): ntf mu 0 3.1 s, Nagata 6.3 s,
//! ntf mu 0.3 9.3 s, mortar mu 0.3 190.6 s (mortar mu 0: 153 s in the
//! hold's table above). The figures of the report (`ironing_3d_forces.svg`,
//! `ironing_3d_iterations.svg`) are this run's.
//! Since the hold of frictional nodes (the Nagata section below), `ntf
//! faceted mu 0.3` is 27 / 229 / 0, `F_n` oscillation 0.0886, `F_t / F_n`
//! 0.3893, 8.85 its per slide increment (`ctc run --threads 1` of the
//! deck, debug), the mortar / faceted ratio at mu 0.3 0.739; the other
//! rows do not move (no frictional node-to-facet pair).

use super::friction_ntf_3d::Rows;
use super::{error, value};
use crate::case::{Check, Quantity};
use crate::measure::Value;
use crate::plot::{Curve, Figure, Panel};
use crate::registry::{CaseKind, ProgramCase, ProgramLevel, VerifyCase};
use ctc_engine::model::AnyModel;
use ctc_engine::solve::{run, IncrementView, Observer, RunSummary};

/// Friction coefficient of the frictional variants.
pub const MU: f64 = 0.3;

/// End of the slide (analysis time).
const END: f64 = 2.0;

/// One contact discretization of the comparison.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Variant {
    /// Label (legends, quantity names).
    pub label: &'static str,
    /// `formulation = ..` of the contact block.
    pub formulation: &'static str,
    /// `smoothing = ..` of the contact block.
    pub smoothing: &'static str,
    /// Friction coefficient (0: frictionless).
    pub mu: f64,
}

/// The variants, rows of the comparison table.
pub const VARIANTS: [Variant; 6] = [
    Variant {
        label: "ntf faceted mu 0",
        formulation: "node_to_segment",
        smoothing: "none",
        mu: 0.0,
    },
    Variant {
        label: "ntf nagata mu 0",
        formulation: "node_to_segment",
        smoothing: "nagata",
        mu: 0.0,
    },
    Variant {
        label: "mortar mu 0",
        formulation: "mortar",
        smoothing: "none",
        mu: 0.0,
    },
    Variant {
        label: "ntf faceted mu 0.3",
        formulation: "node_to_segment",
        smoothing: "none",
        mu: MU,
    },
    Variant {
        label: "mortar mu 0.3",
        formulation: "mortar",
        smoothing: "none",
        mu: MU,
    },
    Variant {
        label: "ntf nagata mu 0.3",
        formulation: "node_to_segment",
        smoothing: "nagata",
        mu: MU,
    },
];

/// The variants run at each level (indices into [`VARIANTS`]).
pub const LEVEL_VARIANTS: [&[usize]; 2] = [&[3, 5], &[0, 1, 2, 3, 4, 5]];

/// Quantity names of each variant: end time, `F_n` oscillation, the
/// tangential figure (`F_t / F_n` with friction, `(max - min) F_t / mean
/// F_n` without), Newton iterations per slide increment, increments,
/// cutbacks, contact force vs die reaction.
pub const NAMES: [[&str; 7]; 6] = [
    [
        "ntf faceted mu 0: end time",
        "ntf faceted mu 0: F_n oscillation (max-min)/mean",
        "ntf faceted mu 0: F_t (max-min) / mean F_n",
        "ntf faceted mu 0: Newton iterations per slide increment",
        "ntf faceted mu 0: increments",
        "ntf faceted mu 0: cutbacks",
        "ntf faceted mu 0: contact force vs die reaction",
    ],
    [
        "ntf nagata mu 0: end time",
        "ntf nagata mu 0: F_n oscillation (max-min)/mean",
        "ntf nagata mu 0: F_t (max-min) / mean F_n",
        "ntf nagata mu 0: Newton iterations per slide increment",
        "ntf nagata mu 0: increments",
        "ntf nagata mu 0: cutbacks",
        "ntf nagata mu 0: contact force vs die reaction",
    ],
    [
        "mortar mu 0: end time",
        "mortar mu 0: F_n oscillation (max-min)/mean",
        "mortar mu 0: F_t (max-min) / mean F_n",
        "mortar mu 0: Newton iterations per slide increment",
        "mortar mu 0: increments",
        "mortar mu 0: cutbacks",
        "mortar mu 0: contact force vs die reaction",
    ],
    [
        "ntf faceted mu 0.3: end time",
        "ntf faceted mu 0.3: F_n oscillation (max-min)/mean",
        "ntf faceted mu 0.3: F_t / F_n (slide mean) vs mu",
        "ntf faceted mu 0.3: Newton iterations per slide increment",
        "ntf faceted mu 0.3: increments",
        "ntf faceted mu 0.3: cutbacks",
        "ntf faceted mu 0.3: contact force vs die reaction",
    ],
    [
        "mortar mu 0.3: end time",
        "mortar mu 0.3: F_n oscillation (max-min)/mean",
        "mortar mu 0.3: F_t / F_n (slide mean) vs mu",
        "mortar mu 0.3: Newton iterations per slide increment",
        "mortar mu 0.3: increments",
        "mortar mu 0.3: cutbacks",
        "mortar mu 0.3: contact force vs die reaction",
    ],
    [
        "ntf nagata mu 0.3: end time",
        "ntf nagata mu 0.3: F_n oscillation (max-min)/mean",
        "ntf nagata mu 0.3: F_t / F_n (slide mean) vs mu",
        "ntf nagata mu 0.3: Newton iterations per slide increment",
        "ntf nagata mu 0.3: increments",
        "ntf nagata mu 0.3: cutbacks",
        "ntf nagata mu 0.3: contact force vs die reaction",
    ],
];

/// The comparisons: `(name, variant, faceted variant, F_t)`, the ratio of
/// the `F_n` oscillations (`(max - min) / mean` over `t >= 1.5`), or with
/// `F_t` of the `F_t` spreads (`(max - min) F_t / mean F_n`, the same
/// window).
pub const RATIOS: [(&str, usize, usize, bool); 5] = [
    ("F_n oscillation: ntf nagata / faceted (mu 0)", 1, 0, false),
    ("F_n oscillation: mortar / ntf faceted (mu 0)", 2, 0, false),
    (
        "F_n oscillation: mortar / ntf faceted (mu 0.3)",
        4,
        3,
        false,
    ),
    (
        "F_n oscillation: ntf nagata / faceted (mu 0.3)",
        5,
        3,
        false,
    ),
    ("F_t oscillation: ntf nagata / faceted (mu 0.3)", 5, 3, true),
];

/// The deck of variant `v` at `level` (0: slab 6 x 3 x 2, die 28 x 3,
/// press 0.5 in 3 increments, slide 1.0 in 8; 1: the benchmark, slab 9 x
/// 3 x 4, die 28 x 5, press 1.4 in 7, slide 4.0 in 20).
pub fn deck(level: usize, v: &Variant) -> String {
    deck_with(&Setup::level(level), v)
}

/// The geometry, meshes and penalty of a deck: a level's, refined (the
/// normal-force study of issue 18: `F_n` against the slab's cell size,
/// the die's faceting and the penalty; the plane-strain slab against the
/// 2D run of the same section, [`deck_2d`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Setup {
    /// Slab length (x) and width (z).
    pub length: usize,
    /// Slab width along z.
    pub width: usize,
    /// Slab cells along x and y (of size 1 / `refine`): `length * refine`,
    /// `3 * refine`.
    pub refine: usize,
    /// Slab cells along z.
    pub cells_z: usize,
    /// Die facets along its arc (200..340 degrees).
    pub facets: usize,
    /// Die cells along z.
    pub layers: usize,
    /// Press depth and slide length.
    pub press: f64,
    /// Slide along x.
    pub slide: f64,
    /// Increments of the press and the slide (0: no slide step).
    pub increments: (usize, usize),
    /// Area penalty.
    pub penalty: f64,
    /// `u_z = 0` on the slab's faces `z = z0` and `z = z0 + width`: the
    /// 3D slab in plane strain.
    pub plane_strain: bool,
}

impl Setup {
    /// The deck of [`deck`] at `level`.
    pub fn level(level: usize) -> Setup {
        let mut s = Setup {
            length: 6,
            width: 2,
            refine: 1,
            cells_z: 2,
            facets: 28,
            layers: 3,
            press: 0.5,
            slide: 1.0,
            increments: (3, 8),
            penalty: 500.0,
            plane_strain: false,
        };
        if level > 0 {
            s.length = 9;
            s.width = 4;
            s.cells_z = 4;
            s.layers = 5;
            s.press = 1.4;
            s.slide = 4.0;
            s.increments = (7, 20);
        }
        s
    }
}

/// The contact block's lines of variant `v` with area penalty `penalty`.
fn contact_lines(v: &Variant, penalty: f64) -> String {
    let mut contact = format!(
        "  method = penalty {{ kind = area  stiffness = {penalty} }}\n  formulation = {}\n",
        v.formulation
    );
    if v.smoothing != "none" {
        contact.push_str(&format!("  smoothing = {}\n", v.smoothing));
    }
    if v.mu > 0.0 {
        contact.push_str(&format!("  friction = coulomb {{ mu = {} }}\n", v.mu));
    }
    contact
}

/// The steps of `s` (press `0..1`, slide `1..2`; no slide with no slide
/// increments).
fn steps(s: &Setup) -> String {
    let mut out = format!(
        "step press {{ time = 0 .. 1  increments = {}  newton {{ tol = 1e-8  max_iter = 30 }} }}\n",
        s.increments.0
    );
    if s.increments.1 > 0 {
        out.push_str(&format!(
            "step slide {{ time = 1 .. 2  increments = {}  newton {{ tol = 1e-8  max_iter = 30 }} }}\n",
            s.increments.1
        ));
    }
    out
}

/// The 3D deck of variant `v` on setup `s`.
pub fn deck_with(s: &Setup, v: &Variant) -> String {
    let (length, width, r) = (s.length, s.width, s.refine);
    let die = width as f64 + 1.2;
    let contact = contact_lines(v, s.penalty);
    let symmetry = if s.plane_strain {
        "fix slab.zmin { uz }\nfix slab.zmax { uz }\n"
    } else {
        ""
    };
    format!(
        "# Ironing ({}), generated by verification/src/programs/ironing_3d.rs\n\
         analysis {{ dimension = 3d }}\n\
         material slab_mat {{ neo_hookean {{ E = 1  nu = 0.3 }} }}\n\
         material die_mat {{ neo_hookean {{ E = 1000  nu = 0.499 }} }}\n\
         body slab {{\n  mesh = box {{ origin = (0, 0, 0.6)  size = ({length}, 3, {width})  divisions = ({}, {}, {}) }}\n  material = slab_mat\n  kinematics = finite\n}}\n\
         body die {{\n  mesh = extrude {{\n    base = annulus {{ center = (2, 6)  inner = 2  outer = 3  start = 200  end = 340  radial = 1  circumferential = {} }}\n    length = {die}\n    layers = {}\n  }}\n  material = die_mat\n  kinematics = finite\n}}\n\
         contact slab.ymax -> die.outer {{\n{contact}}}\n\
         fix slab.ymin {{ ux uy uz }}\n{symmetry}\
         displace die.inner {{\n  ux = table((0, 0), (1, 0), (2, {}))\n  uy = table((0, 0), (1, -{}), (2, -{}))\n  uz = 0\n}}\n{}",
        v.label,
        length * r,
        3 * r,
        s.cells_z,
        s.facets,
        s.layers,
        s.slide,
        s.press,
        s.press,
        steps(s),
    )
}

/// The plane-strain deck of the slab's and the die's `x-y` section on
/// setup `s` (the same cells along x and y, the same die facets) with
/// `formulation` (`node_to_segment` or `mortar`), frictionless: the
/// reference of the 3D slab in plane strain, its force per unit width.
pub fn deck_2d(s: &Setup, formulation: &'static str) -> String {
    let v = Variant {
        label: "2d",
        formulation,
        smoothing: "none",
        mu: 0.0,
    };
    let contact = contact_lines(&v, s.penalty);
    format!(
        "# Ironing in plane strain ({formulation}), generated by verification/src/programs/ironing_3d.rs\n\
         analysis {{ dimension = plane_strain }}\n\
         material slab_mat {{ neo_hookean {{ E = 1  nu = 0.3 }} }}\n\
         material die_mat {{ neo_hookean {{ E = 1000  nu = 0.499 }} }}\n\
         body slab {{\n  mesh = rectangle {{ origin = (0, 0)  size = ({}, 3)  divisions = ({}, {}) }}\n  material = slab_mat\n  kinematics = finite\n}}\n\
         body die {{\n  mesh = annulus {{ center = (2, 6)  inner = 2  outer = 3  start = 200  end = 340  radial = 1  circumferential = {} }}\n  material = die_mat\n  kinematics = finite\n}}\n\
         contact slab.top -> die.outer {{\n{contact}}}\n\
         fix slab.bottom {{ ux uy }}\n\
         displace die.inner {{\n  ux = table((0, 0), (1, 0), (2, {}))\n  uy = table((0, 0), (1, -{}), (2, -{}))\n}}\n{}",
        s.length,
        s.length * s.refine,
        3 * s.refine,
        s.facets,
        s.slide,
        s.press,
        s.press,
        steps(s),
    )
}

/// What one run measured.
#[derive(Debug, Clone)]
pub struct IroningRun {
    /// `(time, F_t, F_n)` per converged increment: the force of the die on
    /// the slab, `F_t` along +x, `F_n` along -y.
    pub history: Vec<(f64, f64, f64)>,
    /// `(time, Newton iterations)` per converged increment.
    pub iterations: Vec<(f64, usize)>,
    /// Time of the last converged increment.
    pub end: f64,
    /// `(max - min) / mean` of `F_n` over `t >= 1.5`.
    pub oscillation: f64,
    /// Mean of `F_t / F_n` over `t > 1.25`.
    pub ratio: f64,
    /// `(max - min)` of `F_t` over the mean `F_n`, `t >= 1.5`.
    pub tangential: f64,
    /// Mean Newton iterations per converged increment of the slide.
    pub slide_iterations: f64,
    /// Largest `|contact force - die reaction| / |contact force|`.
    pub balance: f64,
    /// Largest `|T . n| / |T|` over the closed slab nodes of every
    /// converged increment with a friction force (`n` the normal the node
    /// reports: the patch's on a Nagata die): the friction acts in the
    /// tangent plane of the normal that gives the gap.
    pub tangent_plane: f64,
    /// Why the run stopped before the end (`None`: it completed).
    pub stopped: Option<String>,
    /// The run's summary (up to where it stopped).
    pub summary: RunSummary,
}

/// Runs variant `v` at `level`. A run that stops before the end is
/// measured up to where it stopped (its end time says so); one without a
/// converged increment in the second half of the slide is an error.
pub fn run_variant(level: usize, v: &Variant) -> Result<IroningRun, String> {
    let name = format!("ironing_3d level {level} {}", v.label);
    let text = deck(level, v);
    let src = ctc_lang::Source::new(std::path::Path::new("ironing_3d.ctc"), &text);
    let AnyModel::D3(model) = ctc_lang::compile_any(&src).map_err(|d| d.render(&src))? else {
        return Err(format!("{name}: not a 3d deck"));
    };
    let mut nodes: Vec<usize> = model
        .mesh
        .face_sets
        .get("die.inner")
        .ok_or("no face set die.inner")?
        .iter()
        .flat_map(|f| f.nodes().to_vec())
        .collect();
    nodes.sort_unstable();
    nodes.dedup();
    let mut rows = Rows::on(nodes);
    let (summary, stopped) = match run(&model, &mut rows) {
        Ok(s) => (s, None),
        Err(e) => (e.summary, Some(e.message)),
    };
    let mut history = Vec::new();
    let mut balance = 0.0f64;
    let mut tangent_plane = 0.0f64;
    for (t, contact, reaction) in &rows.rows {
        for c in contact {
            let tr = c.friction.traction;
            let len = (tr[0] * tr[0] + tr[1] * tr[1] + tr[2] * tr[2]).sqrt();
            if len > 1e-12 {
                let tn = (0..3).map(|k| tr[k] * c.normal[k]).sum::<f64>();
                tangent_plane = tangent_plane.max(tn.abs() / len);
            }
        }
        let mut f = [0.0; 3];
        for c in contact {
            for (fk, ck) in f.iter_mut().zip(c.force) {
                *fk += ck;
            }
        }
        let norm = (f[0] * f[0] + f[1] * f[1] + f[2] * f[2]).sqrt();
        if norm > 0.0 {
            let d = (0..3).map(|k| (f[k] - reaction[k]).powi(2)).sum::<f64>();
            balance = balance.max(d.sqrt() / norm);
        }
        // the slab's contact force is the die's push on it: down (-y) and
        // dragged along +x
        history.push((*t, f[0], -f[1]));
    }
    let end = history.last().map_or(0.0, |h| h.0);
    let late: Vec<&(f64, f64, f64)> = history.iter().filter(|h| h.0 >= 1.5 - 1e-9).collect();
    if late.len() < 2 {
        return Err(format!(
            "{name}: fewer than two increments in the second half of the slide (stopped at t = {end}: {})",
            stopped.as_deref().unwrap_or("-")
        ));
    }
    let spread = |pick: fn(&(f64, f64, f64)) -> f64| {
        late.iter()
            .map(|h| pick(h))
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
                (a.min(x), b.max(x))
            })
    };
    let mean_n = late.iter().map(|h| h.2).sum::<f64>() / late.len() as f64;
    let (lo, hi) = spread(|h| h.2);
    let (tlo, thi) = spread(|h| h.1);
    let slide: Vec<&(f64, f64, f64)> = history.iter().filter(|h| h.0 > 1.25).collect();
    let ratio = slide.iter().map(|h| h.1 / h.2).sum::<f64>() / slide.len() as f64;
    let iterations: Vec<(f64, usize)> = summary
        .increments
        .iter()
        .map(|i| (i.time, i.iterations))
        .collect();
    let slide_its: Vec<usize> = iterations
        .iter()
        .filter(|i| i.0 > 1.0 + 1e-12)
        .map(|i| i.1)
        .collect();
    Ok(IroningRun {
        end,
        oscillation: (hi - lo) / mean_n,
        ratio,
        tangential: (thi - tlo) / mean_n,
        slide_iterations: slide_its.iter().sum::<usize>() as f64 / slide_its.len().max(1) as f64,
        balance,
        tangent_plane,
        stopped,
        history,
        iterations,
        summary,
    })
}

/// The measured values of variant `k`'s run `r`.
fn values(k: usize, r: &IroningRun) -> Vec<Value> {
    let n = &NAMES[k];
    let tangential = if VARIANTS[k].mu > 0.0 {
        value(n[2], r.ratio, VARIANTS[k].mu)
    } else {
        error(n[2], r.tangential)
    };
    let mut out = vec![
        value(n[0], r.end, END),
        error(n[1], r.oscillation),
        tangential,
        error(n[3], r.slide_iterations),
        error(n[4], r.summary.increments.len() as f64),
        error(n[5], r.summary.cutbacks as f64),
        error(n[6], r.balance),
    ];
    if k == NAGATA_FRICTION {
        out.push(error(TANGENT_PLANE, r.tangent_plane));
    }
    out
}

/// The variant of friction on Nagata patches.
pub const NAGATA_FRICTION: usize = 5;

/// Its friction force against the patch's normal at every slab node.
pub const TANGENT_PLANE: &str =
    "ntf nagata mu 0.3: max |T . n| / |T| over the nodes (n the patch's normal)";

/// The figures of the runs: forces and iterations against time.
fn figures(runs: &[(usize, IroningRun)]) -> Vec<Figure> {
    let curve = |k: usize, points: Vec<(f64, f64)>| Curve {
        label: VARIANTS[k].label.to_string(),
        points,
    };
    let panel = |title: &str, y: &str, pick: &dyn Fn(&IroningRun) -> Vec<(f64, f64)>| Panel {
        title: title.to_string(),
        x_desc: "time (0..1 press, 1..2 slide)".to_string(),
        y_desc: y.to_string(),
        curves: runs.iter().map(|(k, r)| curve(*k, pick(r))).collect(),
    };
    vec![
        Figure {
            name: "forces".into(),
            panels: vec![
                panel("ironing_3d: normal force F_n of the die", "F_n", &|r| {
                    r.history.iter().map(|h| (h.0, h.2)).collect()
                }),
                panel("ironing_3d: tangential force F_t of the die", "F_t", &|r| {
                    r.history.iter().map(|h| (h.0, h.1)).collect()
                }),
            ],
        },
        Figure {
            name: "iterations".into(),
            panels: vec![panel(
                "ironing_3d: Newton iterations per increment",
                "Newton iterations",
                &|r| r.iterations.iter().map(|i| (i.0, i.1 as f64)).collect(),
            )],
        },
    ]
}

fn ironing_level(level: usize) -> Result<ProgramLevel, String> {
    let mut out = ProgramLevel {
        h: 1.0 / (1usize << level) as f64,
        ..ProgramLevel::default()
    };
    // the runs are independent: each on its own thread (the same bits
    // whatever the thread count; the case's wall time is its longest run)
    let variants = LEVEL_VARIANTS.get(level).ok_or("no such level")?;
    let results: Vec<Result<IroningRun, String>> = std::thread::scope(|scope| {
        let handles: Vec<_> = variants
            .iter()
            .map(|&k| scope.spawn(move || run_variant(level, &VARIANTS[k])))
            .collect();
        handles
            .into_iter()
            .map(|h| h.join().unwrap_or_else(|_| Err("the run panicked".into())))
            .collect()
    });
    let mut runs = Vec::new();
    for (&k, r) in variants.iter().zip(results) {
        let r = r?;
        out.add_run(&r.summary);
        out.values.extend(values(k, &r));
        runs.push((k, r));
    }
    let osc = |k: usize, t: bool| {
        runs.iter()
            .find(|r| r.0 == k)
            .map(|r| if t { r.1.tangential } else { r.1.oscillation })
    };
    for (name, a, b, t) in RATIOS {
        if let (Some(x), Some(y)) = (osc(a, t), osc(b, t)) {
            out.values.push(error(name, x / y));
        }
    }
    out.figures = figures(&runs);
    Ok(out)
}

/// The checks: per variant the tolerances of [`LEVEL_FIGURES`], the
/// force balance 1e-6 (measured 1.0e-8: Newton's tolerance 1e-8), the
/// ratios [`RATIO_TOLERANCES`].
fn checks() -> Vec<Check> {
    let named = |q: &'static str, t: &[f64]| Check::new(Quantity::Named(q), t);
    let mut out = Vec::new();
    for (k, names) in NAMES.iter().enumerate() {
        let [end, osc, tangential, its] = LEVEL_FIGURES[k];
        out.push(named(names[0], &end));
        out.push(named(names[1], &osc));
        out.push(named(names[2], &tangential));
        out.push(named(names[3], &its));
        out.push(named(names[6], &[1e-6, 1e-6]));
    }
    for (name, tolerance) in RATIOS.iter().map(|r| r.0).zip(RATIO_TOLERANCES) {
        out.push(named(name, &tolerance));
    }
    out.push(named(TANGENT_PLANE, &[1e-12, 1e-12]));
    out
}

/// Tolerances per variant, `[level 0, level 1]` (a variant not run at
/// level 0 has its level-1 value there): the end time's relative error,
/// the `F_n` oscillation, the tangential figure (`F_t / F_n` against mu
/// with friction, `(max - min) F_t / mean F_n` without), the Newton
/// iterations per slide increment. The measured figures rounded up (the
/// faceted die makes the force history path-sensitive: `ironing_ntf_3d`'s
/// `F_n` oscillation moved 0.094 -> 0.134 after a change of the sparsity
/// pattern alone). Measured: level 0 by `ctc verify ironing_3d -j 1
/// --json` (debug); level 1 by `ctc run -v` (debug) of the decks of
/// [`deck`] (`history.csv`, `summary.json`, the definitions of
/// [`run_variant`]), the node-to-facet mu = 0.3 row also by the catalogue's
/// `ironing_ntf_3d` (the same deck), the mortar rows by issue 18's table
/// (stop 41, helper mpopp).
pub const LEVEL_FIGURES: [[[f64; 2]; 4]; 6] = [
    // ntf faceted mu 0: 0.115, 0.059, 5.43 (95 increments, 22 cutbacks);
    // since the node-to-facet hold (`mortar::HOLD_BAND`): 0.032, 0.057,
    // 6.29 (31 increments, 2 cutbacks; before it, on the main of stop 46,
    // it stopped at t = 1.8725: `ctc verify ironing_3d --max-level 1
    // --report`, release); with the memory rule 0.032, 0.052, 6.80 (27
    // increments, no cutback; the module doc's level-1 table)
    [[1e-9, 1e-9], [0.2, 0.2], [0.08, 0.08], [8.0, 8.0]],
    // ntf nagata mu 0: 0.027, 0.048, 6.56 (64 increments, 13 cutbacks);
    // with the hold 0.026, 0.047, 5.95 (27 increments, no cutback)
    [[1e-9, 1e-9], [0.05, 0.05], [0.07, 0.07], [9.0, 9.0]],
    // mortar mu 0: 0.038, 0.019, 5.96 (87 increments, 17 cutbacks; it
    // reaches t = 2 on the main of stop 42, where the stop-41 binary
    // stopped at t = 1.70: `ctc verify ironing_3d --max-level 1 -j 2`,
    // debug, 2,448 s wall)
    [[1e-9, 1e-9], [0.05, 0.05], [0.03, 0.03], [8.0, 8.0]],
    // ntf faceted mu 0.3: level 0 F_n oscillation 0.079, F_t / F_n 0.302
    // (error 8e-3), 7.45 iterations; level 1 0.134, 0.396, 10.0 (0.091,
    // 0.391 by `ironing_ntf_3d` with the first-touch crossing following the
    // iterate); with the memory rule and `friction_facet::CONE_TIE`: level
    // 0 0.079, 0.2998, 5.80 (16 increments, 3 cutbacks in the press);
    // level 1 0.091, 0.390, 10.45 (27 increments, no cutback); with the
    // hold of frictional nodes (`DeformablePair::hold_friction`): level 0
    // 0.0749, 0.3050 (error 0.017), 6.75 (11 increments, no cutback);
    // level 1 0.0886, 0.3893, 8.85 (27 increments, no cutback)
    [[1e-9, 1e-9], [0.15, 0.2], [0.03, 0.4], [10.0, 12.0]],
    // mortar mu 0.3: 0.065, 0.341, 10.0; with the first-touch stick
    // point 0.067, 0.340, 10.0 (t = 2, 54 increments, 12 cutbacks, none
    // at the second press increment: `ctc run` of [`deck`], debug); with
    // mortar's cone tie (`friction3d::respond`, a trial on the cone to
    // round-off slips) 0.0667, 0.3408, 8.41: 56 increments, 720 its, 9
    // cutbacks, 310 s CPU, largest |F_z| 1.9e-13, against 37 / 442 / 4,
    // 164 s, 0.0655, 0.3394, 11.77 and |F_z| 6.2e-9 without it (`ctc run
    // --threads 1` of the level-1 deck, debug, both binaries): the
    // symmetry is kept, the benchmark's slide costs 1.6 times the
    // iterations (level 0's deck: 103 -> 69 its, 1 -> 0 cutbacks)
    [[1e-9, 1e-9], [0.1, 0.1], [0.2, 0.2], [12.0, 12.0]],
    // ntf nagata mu 0.3 (friction on Nagata patches, `friction_nagata`):
    // level 0 0.0700, 0.2940 (error 0.020), 9.29 (19 increments, 3
    // cutbacks); level 1 0.0870, 0.3680 (0.227), 8.83 (60 increments, 11
    // cutbacks); with the hold of frictional nodes: level 0 0.0695,
    // 0.2938 (0.021), 8.50 (11 increments, no cutback); level 1 0.0872,
    // 0.3670 (0.223), 8.36 (32 increments, 2 cutbacks): the module doc's
    // Nagata table
    [[1e-9, 1e-9], [0.1, 0.1], [0.03, 0.3], [12.0, 12.0]],
];

/// Tolerances of [`RATIOS`] (level 1): nagata / faceted 0.23, mortar /
/// faceted 0.33 (mu 0) and 0.48 (mu 0.3), measured by the run of
/// [`LEVEL_FIGURES`]; since the node-to-facet hold (`mortar::HOLD_BAND`)
/// 0.788, 1.144 and 0.705 (`ctc verify ironing_3d --max-level 1
/// --report`, release): the faceted run's `F_n` oscillation at mu 0 was
/// mostly its chatter (0.115 -> 0.032: two slab nodes lost through the
/// die and found back at every increment), the faceted die's own is now
/// below mortar's (0.037) and above Nagata's (0.026). The mu 0.3 ratio
/// (0.0655 / 0.0929) was past 0.7 before the hold: neither run changes
/// with it (frictional pairs held nothing then), and 52fee49 measured 0.066
/// for mortar, `docs/ARCHITECTURE.md` 0.0929 for `ironing_ntf_3d`. With
/// the memory rule and `friction_facet::CONE_TIE` (the module doc's
/// level-1 table): 0.790, 1.148, 0.718. Nagata / faceted at mu = 0.3
/// (level 0, level 1; the module doc's Nagata table): `F_n` 0.884, 0.953
/// (not worse than faceted: 1.0), `F_t` spread 0.574, 0.967; with the
/// hold of frictional nodes `F_n` 0.927, 0.984, `F_t` spread 0.533, 1.059
/// (the faceted run's spread fell more, 0.0523 -> 0.0472, than Nagata's,
/// 0.0506 -> 0.0500: level 1's `F_t` bound 1.0 -> 1.1). The mortar run
/// does not change with it; its ratio to `ntf faceted mu 0.3` moves 0.718
/// -> 0.739 (the faceted `F_n` oscillation 0.0913 -> 0.0886).
pub const RATIO_TOLERANCES: [[f64; 2]; 5] =
    [[0.9, 0.9], [1.3, 1.3], [0.8, 0.8], [1.0, 1.0], [0.8, 1.1]];

/// Quantities of `ironing_plane_strain_3d`.
pub const PLANE_NAMES: [&str; 6] = [
    "mortar: F_n per width, 3D slab in plane strain vs 2D",
    "node-to-facet: F_n per width, 3D slab in plane strain vs 2D node-to-segment",
    "2D: F_n mortar vs node-to-segment",
    "3D: F_n mortar vs node-to-facet (plane strain)",
    "2D slide, slab cells halved: mean F_n over t >= 1.5, node-to-segment vs mortar",
    "2D node-to-segment slide, slab cells halved: min F_n over the slide vs F_n at t = 1",
];

/// The press of `ironing_plane_strain_3d` at `level`: the benchmark's
/// section (slab 9 x 3, die 28 facets, area penalty 500, press 1.4 in 7
/// increments, no slide), slab cells of size `1 / 2^level`, in 3D one cell
/// across the slab's width 4 held by `u_z = 0` on both faces and one layer
/// of die cells (nothing depends on z: the die's 5 layers of the
/// benchmark give 2.85749 where one gives 2.85751, mortar, level 0, `ctc
/// run` release; the mortar press costs 16 s of CPU with 5, 2.8 s with 1).
pub fn plane_setup(level: usize) -> Setup {
    Setup {
        refine: 1 << level,
        cells_z: 1,
        layers: 1,
        increments: (7, 0),
        plane_strain: true,
        ..Setup::level(1)
    }
}

/// The slide of `ironing_plane_strain_3d` at `level`: the 2D section of
/// [`plane_setup`] with slab cells of half the level's size (`1 /
/// 2^(level + 1)`: the defect it guards showed at cells 1/2 and 1/4, not
/// at 1) and the benchmark's slide (4.0 in 20 increments after the
/// press).
pub fn slide_setup(level: usize) -> Setup {
    Setup {
        refine: 2 << level,
        increments: (7, 20),
        ..plane_setup(level)
    }
}

/// The slave's total contact force along y at every converged increment.
#[derive(Default)]
struct Forces {
    rows: Vec<(f64, f64)>,
}

impl<const D: usize> Observer<D> for Forces {
    fn converged(&mut self, v: &IncrementView<'_, D>) -> Result<(), String> {
        let fy = v
            .contact
            .first()
            .map_or(0.0, |c| c.iter().map(|n| n.force[1]).sum());
        self.rows.push((v.time, fy));
        Ok(())
    }
}

/// The die's push on the slab `F_n` in a 2D slide run: at the end of
/// the press (`t = 1`), its minimum over the slide (`t > 1`) and its mean
/// over the second half of the slide (`t >= 1.5`).
struct Slide {
    press: f64,
    lowest: f64,
    late: f64,
}

/// Runs the 2D slide of [`slide_setup`] with `formulation` to its end
/// (`t = 2`).
fn slide_2d(
    level: usize,
    formulation: &'static str,
    out: &mut ProgramLevel,
) -> Result<Slide, String> {
    let name = format!("{formulation}_slide_2d.ctc");
    let text = deck_2d(&slide_setup(level), formulation);
    let src = ctc_lang::Source::new(std::path::Path::new(&name), &text);
    let AnyModel::D2(model) = ctc_lang::compile_any(&src).map_err(|d| d.render(&src))? else {
        return Err(format!("{name}: not a 2d deck"));
    };
    let mut forces = Forces::default();
    let summary = run(&model, &mut forces).map_err(|e| format!("{name}: {}", e.message))?;
    let end = forces.rows.last().map_or(0.0, |r| r.0);
    if !summary.completed || (end - END).abs() > 1e-9 {
        return Err(format!("{name}: the slide stopped at t = {end}"));
    }
    out.add_run(&summary);
    let press = forces
        .rows
        .iter()
        .find(|r| (r.0 - 1.0).abs() < 1e-9)
        .ok_or(format!("{name}: no increment at t = 1"))?;
    let lowest = forces
        .rows
        .iter()
        .filter(|r| r.0 > 1.0 + 1e-9)
        .map(|r| -r.1)
        .fold(f64::INFINITY, f64::min);
    let late: Vec<f64> = forces
        .rows
        .iter()
        .filter(|r| r.0 >= 1.5 - 1e-9)
        .map(|r| -r.1)
        .collect();
    Ok(Slide {
        press: -press.1,
        lowest,
        late: late.iter().sum::<f64>() / late.len() as f64,
    })
}

/// The slave's total contact force along y at the last converged
/// increment, and its time.
#[derive(Default)]
struct LastForce {
    time: f64,
    fy: f64,
}

impl<const D: usize> Observer<D> for LastForce {
    fn converged(&mut self, v: &IncrementView<'_, D>) -> Result<(), String> {
        self.time = v.time;
        self.fy = v
            .contact
            .first()
            .map_or(0.0, |c| c.iter().map(|n| n.force[1]).sum());
        Ok(())
    }
}

/// Runs `text` to the end of its press (`t = 1`); the die's push on the
/// slab (`-F_y` of the slab's contact force).
fn press_force(name: &str, text: &str, out: &mut ProgramLevel) -> Result<f64, String> {
    let src = ctc_lang::Source::new(std::path::Path::new(name), text);
    let model = ctc_lang::compile_any(&src).map_err(|d| d.render(&src))?;
    let mut last = LastForce::default();
    let summary = match &model {
        AnyModel::D2(m) => run(m, &mut last),
        AnyModel::D3(m) => run(m, &mut last),
    }
    .map_err(|e| format!("{name}: {}", e.message))?;
    if !summary.completed || (last.time - 1.0).abs() > 1e-9 {
        return Err(format!("{name}: the press stopped at t = {}", last.time));
    }
    out.add_run(&summary);
    Ok(-last.fy)
}

fn plane_strain_level(level: usize) -> Result<ProgramLevel, String> {
    let s = plane_setup(level);
    let mut out = ProgramLevel {
        h: 1.0 / s.refine as f64,
        ..ProgramLevel::default()
    };
    let width = s.width as f64;
    let m3 = press_force(
        "plane_mortar_3d.ctc",
        &deck_with(&s, &VARIANTS[2]),
        &mut out,
    )? / width;
    let n3 = press_force("plane_ntf_3d.ctc", &deck_with(&s, &VARIANTS[0]), &mut out)? / width;
    let m2 = press_force("mortar_2d.ctc", &deck_2d(&s, "mortar"), &mut out)?;
    let n2 = press_force("nts_2d.ctc", &deck_2d(&s, "node_to_segment"), &mut out)?;
    out.values.push(value(PLANE_NAMES[0], m3, m2));
    out.values.push(value(PLANE_NAMES[1], n3, n2));
    out.values.push(value(PLANE_NAMES[2], m2, n2));
    out.values.push(value(PLANE_NAMES[3], m3, n3));
    let nts = slide_2d(level, "node_to_segment", &mut out)?;
    let mortar = slide_2d(level, "mortar", &mut out)?;
    out.values
        .push(value(PLANE_NAMES[4], nts.late, mortar.late));
    out.values
        .push(value(PLANE_NAMES[5], nts.lowest, nts.press));
    Ok(out)
}

/// Tolerances of [`PLANE_NAMES`] per level (slab cells 1, 1/2, 1/4),
/// the measured figures rounded up: `ctc verify ironing_plane_strain_3d
/// --max-level 2 -j 1` (release, 28.6 s CPU): 3D mortar vs 2D 7.4e-6 /
/// 6.7e-6 / 6.5e-6 (the die's deformation: one die layer in 3D); 3D
/// node-to-facet vs 2D node-to-segment 1.0e-2 (the tie at the die's
/// vertex, module doc) / 6.9e-6 / 7.3e-6; 2D mortar vs node-to-segment
/// 9.19e-2 / 1.66e-2 / 2.82e-3 (rate 2.5), 3D 1.03e-1 / 1.66e-2 / 2.82e-3.
/// The slide (slab cells halved, [`slide_setup`]): node-to-segment vs
/// mortar slide mean 2.21e-2 at level 0 (2.965 vs 3.032; before the
/// memory depth rule of `node_to_segment` 1.70: 0.44), the minimum
/// `F_n` over the slide vs the press's end 1.34e-2 (before: 0.97, 0.64),
/// `ctc verify ironing_plane_strain_3d --max-level 0 -j 1` (debug, 15.0 s
/// CPU); levels 1, 2 not run by the case here: at cell 1/4 `ctc run` of
/// the 2D decks gives mortar slide mean 2.999 and 3D node-to-facet 2.987
/// (4e-3; before the fix node-to-segment's 2.83: 5.7e-2).
pub const PLANE_TOLERANCES: [[f64; 3]; 6] = [
    [2e-5, 2e-5, 2e-5],
    [0.015, 2e-5, 2e-5],
    [0.1, 0.025, 0.005],
    [0.12, 0.025, 0.005],
    [0.03, 0.01, 0.01],
    [0.05, 0.05, 0.05],
];

/// The registry entry.
pub fn cases() -> Vec<VerifyCase> {
    let plane = VerifyCase {
        name: "ironing_plane_strain_3d",
        title: "Ironing's press in plane strain (issue 18): the 3D slab held by u_z = 0 on both \
                faces against the 2D plane-strain section, mortar and node-to-facet / \
                node-to-segment; mortar and node-to-segment converge to one force",
        source: "the plane-strain section of the ironing benchmark (Puso & Laursen, CMAME 193 \
                 (2004) 4891-4913) by ctc's 2D node-to-segment and mortar contact",
        tags: &[
            "3d",
            "contact",
            "ironing",
            "deformable",
            "mortar",
            "plane_strain",
        ],
        levels: 1,
        checks: PLANE_NAMES
            .iter()
            .zip(PLANE_TOLERANCES)
            .map(|(q, t)| Check::new(Quantity::Named(q), &t))
            .collect(),
        kind: CaseKind::Program(ProgramCase {
            max_levels: 3,
            run: plane_strain_level,
        }),
    };
    let bench = VerifyCase {
        name: "ironing_3d",
        title: "Ironing in 3D (Puso & Laursen 2004 die-on-slab): node-to-facet faceted / Nagata \
                vs mortar, mu = 0 and 0.3: force histories, their oscillation over the slide, \
                F_t / F_n against mu, Newton iterations per increment",
        source: "M. A. Puso, T. A. Laursen, CMAME 193 (2004) 4891-4913, ironing example",
        tags: &[
            "3d",
            "contact",
            "friction",
            "ironing",
            "deformable",
            "mortar",
            "smoothing",
            "benchmark",
        ],
        levels: 1,
        checks: checks(),
        kind: CaseKind::Program(ProgramCase {
            max_levels: 2,
            run: ironing_level,
        }),
    };
    vec![bench, plane]
}

#[cfg(test)]
mod tests {
    use super::*;
    use ctc_engine::model::{ContactFormulation, NormalSmoothing};

    /// The plane-strain case's decks are one section: at every level the
    /// 3D slab has the 2D slab's nodes in each z plane (cells 1 / 2^level,
    /// one across z, `u_z = 0` on both z faces), the die the 2D die's
    /// facets, and the press is the benchmark's without the slide.
    #[test]
    fn plane_strain_decks_are_one_section() {
        for level in 0..3 {
            let s = plane_setup(level);
            let compile = |text: String| {
                let src = ctc_lang::Source::new(std::path::Path::new("section.ctc"), &text);
                ctc_lang::compile_any(&src).unwrap_or_else(|d| panic!("{}", d.render(&src)))
            };
            let (AnyModel::D3(m3), AnyModel::D2(m2)) = (
                compile(deck_with(&s, &VARIANTS[2])),
                compile(deck_2d(&s, "mortar")),
            ) else {
                panic!("level {level}: the decks' dimensions");
            };
            assert_eq!(
                m3.mesh.nodes.len(),
                2 * m2.mesh.nodes.len(),
                "level {level}"
            );
            let r = 1 << level;
            for side in ["slab.zmin", "slab.zmax"] {
                let c = m3
                    .constraints
                    .iter()
                    .find(|c| c.label.contains(side) && c.component == 2)
                    .unwrap_or_else(|| panic!("level {level}: no u_z = 0 on {side}"));
                assert_eq!(c.nodes.len(), (9 * r + 1) * (3 * r + 1), "level {level}");
            }
            assert_eq!(m3.steps.len(), 1, "the press alone");
            assert_eq!(m2.steps.len(), 1, "the press alone");
            assert_eq!(
                m3.mesh.face_sets["die.outer"].len(),
                m2.mesh.edge_sets["die.outer"].len(),
                "level {level}: one die layer, the 2D die's facets"
            );
        }
    }

    /// The output block of the study's decks: the contact force and the
    /// die's reaction per increment (`history.csv`).
    fn with_history(deck: String, dim3: bool) -> String {
        let top = if dim3 { "slab.ymax" } else { "slab.top" };
        format!(
            "{deck}output {{\n  history = [contact_force({top} -> die.outer), reaction(die.inner)]\n}}\n"
        )
    }

    /// Writes the decks of the normal-force study of issue 18 into
    /// `$IRONFN_DECKS` (default `target/ironing_fn_decks`) for `ctc run`
    /// (release, `--threads 1`): the frictionless variants on the
    /// benchmark (level 1) at the penalty x1 and x10, on a slab of half
    /// the cell size and on a die of twice the facets; the same on the
    /// slab in plane strain (`u_z = 0` on both z faces, one cell across:
    /// the solution does not depend on z) at 1, 1/2, 1/4 of the cell size,
    /// and the 2D plane-strain section with node-to-segment and mortar at
    /// 1 .. 1/8. `cargo test -p ctc-verification --lib --
    /// --ignored write_normal_force_study_decks`.
    #[test]
    #[ignore]
    fn write_normal_force_study_decks() {
        let dir = std::env::var("IRONFN_DECKS").unwrap_or("target/ironing_fn_decks".into());
        let dir = std::path::PathBuf::from(dir);
        std::fs::create_dir_all(&dir).expect("decks directory");
        let base = Setup::level(1);
        let tag = |s: &Setup| {
            format!(
                "r{}_z{}_f{}_p{}",
                s.refine, s.cells_z, s.facets, s.penalty as usize
            )
        };
        let write = |name: String, text: String| {
            std::fs::write(dir.join(format!("{name}.ctc")), text).expect("write deck");
        };
        let short = ["ntf", "nagata", "mortar"];
        for p in [500.0, 5000.0] {
            let mut free = vec![base];
            let mut plane = Vec::new();
            let mut planar = Vec::new();
            if p == 500.0 {
                free.push(Setup {
                    refine: 2,
                    cells_z: 8,
                    ..base
                });
                free.push(Setup {
                    facets: 56,
                    layers: 10,
                    ..base
                });
            }
            for r in [1, 2, 4] {
                plane.push(Setup {
                    refine: r,
                    cells_z: 1,
                    plane_strain: true,
                    ..base
                });
            }
            plane.push(Setup {
                cells_z: 4,
                plane_strain: true,
                ..base
            });
            plane.push(Setup {
                facets: 56,
                layers: 10,
                cells_z: 1,
                plane_strain: true,
                ..base
            });
            for r in [1, 2, 4, 8] {
                planar.push(Setup { refine: r, ..base });
            }
            planar.push(Setup { facets: 56, ..base });
            for s in free.iter_mut().chain(&mut plane).chain(&mut planar) {
                s.penalty = p;
            }
            for s in &free {
                for (k, v) in VARIANTS[..3].iter().enumerate() {
                    write(
                        format!("free_{}_{}", short[k], tag(s)),
                        with_history(deck_with(s, v), true),
                    );
                }
            }
            for s in &plane {
                for (k, v) in VARIANTS[..3].iter().enumerate() {
                    write(
                        format!("plane_{}_{}", short[k], tag(s)),
                        with_history(deck_with(s, v), true),
                    );
                }
            }
            for s in &planar {
                for f in ["node_to_segment", "mortar"] {
                    let name = if f == "mortar" { "mortar" } else { "nts" };
                    write(
                        format!("2d_{name}_{}", tag(s)),
                        with_history(deck_2d(s, f), false),
                    );
                }
            }
        }
    }

    /// Every variant's deck compiles at both levels into the contact pair
    /// its row names, and the benchmark level is the deck of
    /// `examples/ironing_3d.ctc` (the slab and die meshes, the die's
    /// motion).
    #[test]
    fn every_variant_deck_is_its_row() {
        for level in 0..2 {
            for v in &VARIANTS {
                let text = deck(level, v);
                let src = ctc_lang::Source::new(std::path::Path::new("ironing_3d.ctc"), &text);
                let model = match ctc_lang::compile_any(&src) {
                    Ok(AnyModel::D3(m)) => m,
                    Ok(_) => panic!("{}: not 3d", v.label),
                    Err(d) => panic!("{}: {}", v.label, d.render(&src)),
                };
                let cp = &model.contacts[0];
                let mortar = v.formulation == "mortar";
                assert_eq!(cp.formulation == ContactFormulation::Mortar, mortar);
                let nagata = cp.smoothing == NormalSmoothing::Nagata;
                assert_eq!(nagata, v.smoothing == "nagata", "{}", v.label);
                assert_eq!(cp.friction.as_ref().map_or(0.0, |f| f.mu), v.mu);
            }
        }
        let bench = deck(1, &VARIANTS[3]);
        let example = std::fs::read_to_string(super::super::examples_dir().join("ironing_3d.ctc"))
            .expect("examples/ironing_3d.ctc");
        for line in [
            "size = (9, 3, 4)  divisions = (9, 3, 4)",
            "circumferential = 28",
            "length = 5.2",
            "layers = 5",
            "ux = table((0, 0), (1, 0), (2, 4))",
            "uy = table((0, 0), (1, -1.4), (2, -1.4))",
            "increments = 7",
            "increments = 20",
        ] {
            assert!(bench.contains(line), "the level-1 deck lacks `{line}`");
            assert!(example.contains(line), "the example lacks `{line}`");
        }
    }
}
