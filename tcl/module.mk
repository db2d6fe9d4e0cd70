# tcl: the Tcl library shipped with molscope.
dist_tcllib_DATA += tcl/init.tcl tcl/vectors.tcl tcl/movie.tcl
# $env(VMDDIR)/tachyon_LINUXAMD64, which VMD scripts run: the system's tachyon
dist_tcllib_SCRIPTS = tcl/tachyon_LINUXAMD64

# VMD's topotools package (doc/topotools.md): Tcl over ::molscope::topo, found through
# auto_path like the other packages here.
topotoolsdir = $(tcllibdir)/topotools
dist_topotools_DATA = tcl/topotools/pkgIndex.tcl tcl/topotools/topotools.tcl

# The page of the live view (display live, doc/live.md).
livepagedir = $(tcllibdir)/live
dist_livepage_DATA = tcl/live/index.html tcl/live/live.tcl

# The molscope::parallel package: a loadable Tcl extension (libtool module) with its
# pkgIndex.tcl, in tcl/parallel/ of the Tcl library. It carries its own copy of the MPI
# layer (src/parallel) and of the argument layer (src/commands/args.c) so it also works in
# a plain tclsh; Tcl stubs when available.
parallelpkgdir = $(tcllibdir)/parallel
parallelpkg_LTLIBRARIES = tcl/parallel/parallel.la
dist_parallelpkg_DATA = tcl/parallel/pkgIndex.tcl
tcl_parallel_parallel_la_SOURCES = tcl/parallel/parallel.c \
	src/parallel/parallel.h src/parallel/internal.h \
	src/parallel/comm.c src/parallel/sched.c src/base/base.c \
	src/commands/args.h src/commands/args.c
tcl_parallel_parallel_la_CFLAGS = $(AM_CFLAGS) $(TCL_STUB_CFLAGS)
tcl_parallel_parallel_la_LDFLAGS = -module -avoid-version -shared
tcl_parallel_parallel_la_LIBADD = $(TCL_STUB_LIBS) $(MPI_LIBS) $(PTHREAD_LIBS)

# VMD's plugin folders on auto_path and vmd_install_extension (sourced by init.tcl).
dist_tcllib_DATA += tcl/vmdplugins.tcl

# VMD's plugin packages molscope ships (doc/pbctools.md, doc/exectool.md), each a folder of
# the Tcl library with its pkgIndex.tcl, found through auto_path.
pbctoolsdir = $(tcllibdir)/pbctools
dist_pbctools_DATA = tcl/pbctools/pkgIndex.tcl tcl/pbctools/pbctools.tcl
exectooldir = $(tcllibdir)/exectool
dist_exectool_DATA = tcl/exectool/pkgIndex.tcl tcl/exectool/exectool.tcl

# VMD's plugin packages, molscope's own code under VMD's names and versions: found through
# auto_path (the Tcl library is on it), loaded by `package require <name>`.
utilitiespkgdir = $(tcllibdir)/utilities
dist_utilitiespkg_DATA = tcl/utilities/pkgIndex.tcl tcl/utilities/utilities.tcl
vmdmoviepkgdir = $(tcllibdir)/vmdmovie
dist_vmdmoviepkg_DATA = tcl/vmdmovie/pkgIndex.tcl tcl/vmdmovie/vmdmovie.tcl
vcrpkgdir = $(tcllibdir)/viewchangerender
dist_vcrpkg_DATA = tcl/viewchangerender/pkgIndex.tcl tcl/viewchangerender/viewchangerender.tcl
