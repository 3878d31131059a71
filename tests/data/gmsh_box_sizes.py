#!/usr/bin/python3
"""Writes gmsh_box_sizes_{41,41_binary,22}.msh: a background grid with a size per node, saved by
gmsh itself (the box of gmsh_box.geo, coarse: mesh size 0.45 at its corners; one $NodeData view
"size" = 0.1 + 0.2 x + 0.3 y + 0.4 z, a linear field). Run in tests/data with /usr/bin/python3
(python3-gmsh)."""
import gmsh

gmsh.initialize()
gmsh.option.setNumber("General.Terminal", 0)
gmsh.model.add("box")
gmsh.model.occ.addBox(0, 0, 0, 1, 1, 0.5)
gmsh.model.occ.synchronize()
gmsh.model.mesh.setSize(gmsh.model.getEntities(0), 0.45)
gmsh.model.mesh.generate(3)
tags, coords, _ = gmsh.model.mesh.getNodes()
sizes = [[0.1 + 0.2 * coords[3 * i] + 0.3 * coords[3 * i + 1] + 0.4 * coords[3 * i + 2]]
         for i in range(len(tags))]
view = gmsh.view.add("size")
gmsh.view.addModelData(view, 0, "box", "NodeData", tags, sizes)
gmsh.option.setNumber("PostProcessing.SaveMesh", 1)
for name, version, binary in (("gmsh_box_sizes_41.msh", 4.1, 0),
                              ("gmsh_box_sizes_41_binary.msh", 4.1, 1),
                              ("gmsh_box_sizes_22.msh", 2.2, 0)):
    gmsh.option.setNumber("Mesh.MshFileVersion", version)
    gmsh.option.setNumber("Mesh.Binary", binary)
    gmsh.view.write(view, name)
gmsh.finalize()
