# src/commands: the Tcl command bindings (thin: parse, call the core, set the result).
src_libmscore_la_SOURCES += \
	src/commands/args.h src/commands/args.c \
	src/commands/commands.h src/commands/cmdsets.c src/commands/cmdutil.c src/commands/cmd_quit.c \
	src/commands/cmd_batch.c src/commands/cmd_gui.c \
	src/commands/cmd_plugin.c src/commands/cmd_timestep.c src/commands/cmd_imd.c \
	src/commands/molinfo.h src/commands/cmd_molinfo.c \
	src/commands/cmd_mol.c src/commands/cmd_animate.c src/commands/cmd_vmdinfo.c \
	src/commands/tclvec.h src/commands/tclvec.c src/commands/cmd_vector.c \
	src/commands/cmd_measure.c src/commands/cmd_measure_geom.c src/commands/cmd_ss.c \
	src/commands/cmd_volmap.c src/commands/cmd_movie.c src/commands/cmd_pbc.c \
	src/commands/cmd_memory.c
# topotools' C half (topo.h)
src_libmscore_la_SOURCES += \
	src/commands/topo.h src/commands/cmd_topo.c src/commands/cmd_topo_build.c
# atomselect and its selection objects (atomsel.h)
src_libmscore_la_SOURCES += \
	src/commands/atomsel.h src/commands/atomsel_int.h src/commands/atomsel.c \
	src/commands/atomsel_getset.c src/commands/atomsel_methods.c
# the scene-side commands (scenecmds.h)
src_libmscore_la_SOURCES += \
	src/commands/scenecmds.h src/commands/cmd_scene.c src/commands/cmd_color.c \
	src/commands/cmd_material.c src/commands/cmd_display.c src/commands/cmd_trans.c \
	src/commands/cmd_graphics.c src/commands/cmd_render.c src/commands/cmd_rep.c \
	src/commands/cmd_live.c src/commands/cmd_label.c \
	src/commands/cmd_state.c
