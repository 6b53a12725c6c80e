"""Writes the skin-pass decks of issue 22 (example 2):

  examples/skin_pass_rough.ctc          the coarse CI variant (roll Ra 30 um, smallest edge 5 um)
  verification/cases/skin_pass_ra30.ctc the full scale, roll Ra 30 um, smallest edge 0.74 um
  verification/cases/skin_pass_ra6.ctc  the full scale, roll Ra 6 um, smallest edge 0.74 um

Run from the repository root: python3 verification/skin_pass/make_decks.py
The roll is a polyline through r(beta) = R + a cos(2 pi R beta / lambda)
(beta from the downward vertical, a crest at the bottom at time 0, Ra =
2 a / pi); the verification program (verification/src/programs/skin_pass.rs)
measures the roll's Ra back from the polyline.
"""
import math

R = 100.0          # roll radius, mm
H = 0.4            # half sheet thickness, mm (0.8 mm sheet, mid-plane symmetry)
MU = 0.15          # Coulomb coefficient roll / sheet
R_MAX = 0.04       # largest nominal reduction the window is sized for


def grade_for(h, top, ny):
    """last / first size ratio of `geometric(r)` with ny rows whose top row is `top`."""
    def top_of(r):
        s = sum(r ** (k / (ny - 1)) for k in range(ny))
        return h * r / s
    lo, hi = 1e-9, 1.0
    for _ in range(200):
        mid = math.sqrt(lo * hi)
        if top_of(mid) > top:
            hi = mid
        else:
            lo = mid
    return math.sqrt(lo * hi)


def deck(header, ra_um, lam, top_um, ny, cells_per_lam, press, step_lam, reduction, every, measured=4, r_max=R_MAX):
    a = math.pi * ra_um / 2 * 1e-3
    top = top_um * 1e-3
    hw = math.sqrt(2 * (R + a) * r_max * H)      # half chord of the crests at the largest descent
    travel = hw + (measured + 1) * lam + 0.1      # the bite's width + the wavelengths measured + margins
    dx = lam / cells_per_lam
    nx = int(math.ceil((travel + hw + 0.3) / dx))
    nx += nx % 2
    length = nx * dx
    grade = grade_for(H, top, ny)
    yc = H + R + a
    bmin = -(hw + 0.3) / R
    bmax = (travel + hw + 0.3) / R
    n = int(math.ceil((bmax - bmin) * R / (lam / 32)))
    pts = []
    for i in range(n + 1):
        b = bmax - i * (bmax - bmin) / n
        r = R + a * math.cos(2 * math.pi * R * b / lam)
        pts.append((r * math.sin(b), yc - r * math.cos(b)))
    xm0 = hw + 0.5 * lam
    xm1 = xm0 + measured * lam
    steps = int(math.ceil(travel / (step_lam * lam)))
    rows = []
    for i in range(0, len(pts), 3):
        rows.append(", ".join(f"({x:.9f}, {y:.9f})" for x, y in pts[i:i + 3]))
    points = ",\n    ".join(rows)
    return f"""{header}
analysis {{ dimension = plane_strain  units = mm_N_s }}

let h = {H}                 # half thickness of the 0.8 mm sheet (mm)
let R = {R}                 # roll radius (mm)
let amplitude = {a:.12f}  # roughness amplitude a (mm): Ra = 2 a / pi = {ra_um} um
let wavelength = {lam}       # roughness wavelength (mm)
let reduction = {reduction}        # nominal reduction: the crests' descent over h
let descent = reduction * h
let travel = {travel:.6f}      # roll travel (mm): the bite + {measured} wavelengths measured
let nx = {nx}                 # columns: wavelength / {cells_per_lam}
let ny = {ny}                  # rows, graded to the top surface
let grade = {grade:.12e}  # bottom / top row ratio: top row {top_um} um

material steel {{
  elastic {{ E = 210 GPa  nu = 0.3 }}
  plastic {{ yield = 250 MPa  hardening = linear {{ H = 1000 MPa }} }}
}}

body sheet {{
  mesh = rectangle {{ origin = (0, 0)  size = ({length:.6f}, h)  divisions = (nx, ny)
                     grading = (uniform, geometric(grade))  element = quad4 }}
  material = steel
  kinematics = finite
  formulation = selective_reduced
}}

# the top nodes that leave the bite during rolling ({measured} wavelengths)
set rolled = sheet.nodes(box(({xm0:.6f}, h - 1e-4), ({xm1:.6f}, h + 1e-4)))

# the rough roll: r(beta) = R + a cos(2 pi R beta / wavelength), a crest at
# the bottom touching the sheet at x = 0; walked clockwise (free side left)
tool roll = polyline {{ points = [
    {points} ]
  motion {{ ux = table((0, 0), (1, 0), (2, travel))
           uy = table((0, 0), (1, -descent), (2, -descent))
           rotation = table((0, 0), (1, 0), (2, -travel / R))
           center = (0, h + R + amplitude) }} }}

contact sheet.top -> roll {{
  method = penalty {{ kind = area  stiffness = 10 * E / h }}
  friction = coulomb {{ mu = {MU} }}
}}

fix sheet.left {{ ux }}
fix sheet.bottom {{ uy }}       # mid-plane of the sheet (symmetric mill)

step press {{ time = 0 .. 1  increments = {press} }}
step roll {{ time = 1 .. 2  increments = {steps} }}

output {{
  every = {every}
  fields = [displacement, von_mises, contact]
  history = [contact_force(sheet.top -> roll), reaction(sheet.bottom), reaction(sheet.left),
             roughness(sheet.rolled)]
}}
"""


COMMON = """# The roll (R = 100 mm) carries a sinusoidal roughness; the sheet is the upper
# half of a 0.8 mm steel sheet (E = 210 GPa, yield 250 MPa, linear hardening
# H = 1000 MPa, finite strain J2, F-bar), held in y on its mid-plane
# (a symmetric two-high mill) and in x at its left end. Only a window of the
# strip is modelled: the bite (half chord sqrt(2 R descent) = 1.8 mm at 4 %)
# plus the 4 wavelengths measured behind it; the rest of the strip only
# carries the window's ends. The roll presses its crests `descent =
# reduction x h` into the sheet (step press), then rolls `travel` along it
# (step roll: rotation -travel / R, no slip far from the bite), Coulomb
# friction mu = 0.15 (penalty 10 E / h). history.csv: the rolling force
# (contact_force), the reactions, and roughness(sheet.rolled): Ra, Rq and
# the mean height of the deformed top nodes of the rolled zone, detrended.
# Transfer ratio = Ra_sheet / Ra_roll; written by verification/skin_pass/make_decks.py.
"""

if __name__ == "__main__":
    coarse = """# Skin pass, coarse CI variant (issue 22 example 2; the seed slides'
# roughness transfer during skin-pass): a smooth steel sheet flattened by a
# rough rigid roll, roll Ra 30 um (wavelength 1 mm), 2 % reduction, cells of
# wavelength / 8, 6 rows with a top row of 5 um, 2 wavelengths measured, the
# window sized for 2 % (the full scale, smallest edge 0.74 um, 4 wavelengths
# measured, sized for 4 %: verification/cases/skin_pass_ra30.ctc and
# skin_pass_ra6.ctc).
""" + COMMON + """# Reference: no closed form; checked by `ctc verify skin_pass` (force balance,
#   Coulomb work, the roll's Ra, the plastic limit of the transfer ratio,
#   verification/src/programs/skin_pass.rs).
# Run: cargo run --release -- run examples/skin_pass_rough.ctc -o out/skin_pass_rough"""
    full30 = """# Skin pass at the domain's scale, roll Ra 30 um (issue 22 example 2; the
# seed slides' roughness transfer during skin-pass): wavelength 1 mm,
# smallest element edge 0.74 um (the top row), cells of wavelength / 16.
""" + COMMON + """# Reference: no closed form; checked by `ctc verify skin_pass --max-level 1`
#   (verification/src/programs/skin_pass.rs).
# Run: cargo run --release -- run verification/cases/skin_pass_ra30.ctc -o out/skin_pass_ra30
#   (reductions: cargo run --release -- sweep verification/cases/skin_pass_ra30.ctc --vary "reduction = 0.01, 0.02, 0.04")"""
    full6 = full30.replace("Ra 30 um", "Ra 6 um").replace("wavelength 1 mm", "wavelength 0.2 mm").replace("ra30", "ra6")
    full30 += """
# Mesh at 1 %: the deformed surface is converged at the nodes (columns of half
#   the width: 4.3e-4 there; half the rows: 1.5e-5), but a dent is about 100 um
#   wide, two 62.5 um columns, and the Ra the nodes sample is about 15 % low at 1 %
#   (0.387 um; 31.25 um columns 0.449 um, within about 3 %). A flat roll leaves
#   0.0012 um (the floor). Figures and commands: verification/src/programs/skin_pass.rs."""
    full6 += """
# Slow (2 %: 143 increments, 2391 iterations, 14 cutbacks): plasticity under the
#   crests (an elastic sheet takes 4 iterations per increment), about 140 Newton
#   iterations per crest imprinted whatever the increment (50 / 25 / 12.5 um: the
#   same iterations per mm), five crests per mm; not friction, not the 0.74 um row.
#   Figures and commands: verification/src/programs/skin_pass.rs."""
    open("examples/skin_pass_rough.ctc", "w").write(deck(coarse, 30, 1.0, 5.0, 6, 8, 2, 1 / 3, 0.02, 5, measured=2, r_max=0.02))
    open("verification/cases/skin_pass_ra30.ctc", "w").write(deck(full30, 30, 1.0, 0.74, 24, 16, 5, 0.125, 0.02, 10))
    open("verification/cases/skin_pass_ra6.ctc", "w").write(deck(full6, 6, 0.2, 0.74, 24, 16, 5, 0.25, 0.02, 10))
