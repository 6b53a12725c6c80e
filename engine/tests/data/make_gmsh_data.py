"""Regenerates the gmsh-written test meshes of this folder.

Needs the gmsh Python package (`pip install gmsh`); the project itself does
not: the .msh files are committed as data. Run from this folder:

    python make_gmsh_data.py
"""
import gmsh


def plate_with_hole(version, path):
    """Quarter of a 2 x 1 plate with a hole of radius 0.3, triangles."""
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add("plate")
    occ = gmsh.model.occ
    plate = occ.addRectangle(0, 0, 0, 2, 1)
    hole = occ.addDisk(0, 0, 0, 0.3, 0.3)
    occ.cut([(2, plate)], [(2, hole)])
    occ.synchronize()
    curves = {}
    for dim, tag in gmsh.model.getEntities(1):
        x, y, _ = gmsh.model.occ.getCenterOfMass(dim, tag)
        if abs(y) < 1e-9:
            curves["bottom"] = tag
        elif abs(x) < 1e-9:
            curves["left"] = tag
        elif abs(x - 2) < 1e-9:
            curves["right"] = tag
        elif abs(y - 1) < 1e-9:
            curves["top"] = tag
        else:
            curves["hole"] = tag
    for name, tag in curves.items():
        gmsh.model.addPhysicalGroup(1, [tag], name=name)
    surf = gmsh.model.getEntities(2)[0][1]
    gmsh.model.addPhysicalGroup(2, [surf], name="plate")
    corner = [t for d, t in gmsh.model.getEntities(0)
              if abs(gmsh.model.getValue(0, t, [])[0] - 2) < 1e-9
              and abs(gmsh.model.getValue(0, t, [])[1] - 1) < 1e-9][0]
    gmsh.model.addPhysicalGroup(0, [corner], name="corner")
    gmsh.option.setNumber("Mesh.MeshSizeMax", 0.25)
    gmsh.option.setNumber("Mesh.MeshSizeMin", 0.05)
    gmsh.model.mesh.setSize([(0, t) for d, t in gmsh.model.getEntities(0)], 0.25)
    gmsh.model.mesh.generate(2)
    gmsh.option.setNumber("Mesh.MshFileVersion", version)
    gmsh.option.setNumber("Mesh.Binary", 0)
    gmsh.write(path)
    gmsh.finalize()


def quarter_disc_quads(version, path):
    """Quarter disc of radius 1 (built-in kernel, centre point off the mesh),
    recombined into quadrangles; arc, axis and flat named."""
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add("quarter")
    geo = gmsh.model.geo
    c = geo.addPoint(0, 0, 0, 0.2)
    a = geo.addPoint(1, 0, 0, 0.2)
    b = geo.addPoint(0, -1, 0, 0.2)
    flat = geo.addLine(c, a)
    arc = geo.addCircleArc(a, c, b)
    axis = geo.addLine(b, c)
    loop = geo.addCurveLoop([flat, arc, axis])
    s = geo.addPlaneSurface([loop])
    geo.synchronize()
    gmsh.model.addPhysicalGroup(1, [arc], name="arc")
    gmsh.model.addPhysicalGroup(1, [axis], name="axis")
    gmsh.model.addPhysicalGroup(1, [flat], name="flat")
    gmsh.model.addPhysicalGroup(2, [s], 7)  # unnamed: physical_7
    gmsh.option.setNumber("Mesh.RecombineAll", 1)
    gmsh.option.setNumber("Mesh.Algorithm", 8)
    gmsh.model.mesh.generate(2)
    gmsh.option.setNumber("Mesh.MshFileVersion", version)
    gmsh.option.setNumber("Mesh.Binary", 0)
    gmsh.write(path)
    gmsh.finalize()


if __name__ == "__main__":
    plate_with_hole(2.2, "gmsh_plate_hole_v22.msh")
    plate_with_hole(4.1, "gmsh_plate_hole_v41.msh")
    quarter_disc_quads(2.2, "gmsh_quarter_disc_quads_v22.msh")
    quarter_disc_quads(4.1, "gmsh_quarter_disc_quads_v41.msh")
