"""vdec plot: pictures of a vdec run (geometry, joints, contact forces, zone stresses, displacements,
plastic states, boundary conditions, histories) drawn with matplotlib, without a display.

Reads a run's folder (DIR/results.json and the VTK snapshots DIR/vtk/*.vtu) and writes one PNG, SVG
or PDF. The geometry comes from the snapshots (results.json holds no vertex positions), so the
run needs `[output] vtk_every` or `--set output.vtk_every=N`. Layers that only results.json holds
(joint states and normals, plastic states) show the end of the run. Usage, layers, colours and
exit codes: docs/user-manual/plot.md. The verification report draws its set-up pictures with
vdec_plot.figures.setup_figure.
"""
