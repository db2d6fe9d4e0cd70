/* molscope.h: the map of molscope's source. Each module has a folder under src/ and one or a
 * few headers with its public API; this header includes them layer by layer, bottom first,
 * so a reader can start here. A unit test compiles it (tests/unit/test_map.c) and
 * tests/python/test_layers.py checks that the modules below and their layers are the ones
 * the sources have (doc/ARCHITECTURE.md explains the layers).
 *
 * Where each stage of the pipeline lives:
 *
 *   file --plugin-->     ../plugins (ms_plugin.h), found and run by fileio/ (registry.h, load.h)
 *   Molecule             molecule/ (molecule.h; the set of them and its events: molset.h)
 *   --selection-->       select/ (select.h)
 *   Rep builders         rep/ (rep.h; one file per drawing method, listed in methods.c)
 *   DisplayList          scene/displaylist.h
 *   Scene                scene/scene.h, assembled from the world by assemble/ (world.h)
 *   --device-->          render/render.h says what a device is; the devices are one table in
 *                        assemble/devices.c: gl/ (snapshot), render/ (Tachyon, POV3,
 *                        Wavefront), rt/ (TachyonInternal), oclrt/ (the OpenCL tracer)
 *   Image                image/ (image.h); movies: movie/
 *   Tcl on top           commands/ (every command, atomselect's included), live/, app/, python/,
 *                        the program in main/
 *
 * The modules, layer by layer (a module includes only its own layer and the layers below):
 *
 *  foundation
 *   base/       utilities: errors, interned strings, worker threads, bit sets, safe file
 *               writing (safewrite.h: a file replaced whole or not at all), the cell grid
 *               of every neighbour search (grid.h)
 *   vecmath/    vectors and 4x4 matrices written once for float (vecf.h) and double
 *               (vecmath.h), 3x3 inverses, VMD's rotations, symmetric eigen-solver
 *  data
 *   molecule/   the Molecule (atoms, bonds, frames, volumes), structure analysis, the
 *               molecule set and its events, serialisation (a molecule as bytes for other
 *               ranks)
 *   fileio/     the plugin registry, loading files into molecules, writing them out
 *   image/      RGB images and their files (PNG, TGA, PPM, BMP)
 *   cl/         what the OpenCL users (surf/, oclrt/) share: errors, device choice, the
 *               one engine (device, context, queue), the per-user cache folders,
 *               programs built or read from the binary cache
 *   imd/        the IMD protocol (a running simulation's coordinates and energies over
 *               TCP): the message codec, the stream decoder, the client connection
 *  core (no Tcl)
 *   ss/         secondary structure computed from the backbone (DSSP), on demand
 *   select/     the atom selection language (compiled to a tree, evaluated to bit sets)
 *   measure/    the numbers behind `measure`: centers, fits, contacts, SASA, g(r) ...
 *   pbc/        periodic boundaries: cells, compounds, wrap/unwrap/join over frames
 *               (the loops behind pbctools' `pbc`, ../tcl/pbctools)
 *   surf/       QuickSurf: Gaussian density maps, marching cubes, the surface engine
 *   parallel/   MPI: start-up and shutdown, collectives, the dynamic for-loop, loading a
 *               file on rank 0 and broadcasting the molecule (also the core of the
 *               molscope::parallel Tcl package, ../tcl/parallel)
 *   movie/      movies: frame files and resuming, frames handed out across ranks, the
 *               ffmpeg encoder fed in frame order, progress (the command: ../tcl/movie.tcl)
 *   scene/      display lists, colours, materials, user graphics, the Scene devices draw,
 *               its lighter level of detail (lod.h)
 *  reps
 *   rep/        representations: selection + drawing method + colouring + material, cached
 *               display lists; one file per drawing method (lines.c ... newcartoon.c)
 *  devices (they see the Scene, images and the helpers below, never a Molecule)
 *   render/     what a render device is, what the devices share, the file exporters
 *   gl/         offscreen OpenGL (OSMesa, EGL): the display device and `render snapshot`
 *   rt/         TachyonInternal: the photorealistic CPU ray tracer on Embree
 *   oclrt/      TachyonLOpenCLInternal: the same tracer on OpenCL
 *  assembly
 *   assemble/   the world (molecules with their reps and user graphics, colours,
 *               materials, the view and its transforms, device settings, display size),
 *               assembling it into the Scene, the table of devices and `render`
 *  Tcl bindings
 *   app/        the application's state (interpreter, molecules, plugins, world: made by
 *               ms_app_new, freed by ms_app_free), command line, shell
 *   commands/   the Tcl command bindings (mol, molinfo, animate, atomselect, measure,
 *               display, color, render ...), listed in commands/cmdsets.c, all on one
 *               argument layer (args.h: subcommand tables, counts, keywords, values,
 *               option lists, one error style)
 *   live/       the live view in a browser: frames rendered at idle, a small web server
 *   python/     Python scripting: gopython, -python, the _molscope module under VMD's
 *               Python API (the molscope package), built with --with-python
 *  program
 *   main/       main(): MPI, the command line, VMD's startup order, the shell
 */
#ifndef MOLSCOPE_H
#define MOLSCOPE_H

/* foundation */
#include "base/base.h"
#include "base/bitset.h"
#include "base/strtab.h"
#include "base/threads.h"
#include "base/safewrite.h"
#include "base/grid.h"
#include "vecmath/vecmath.h"
#include "vecmath/vecf.h"
/* data */
#include "molecule/molecule.h"
#include "molecule/volume.h"
#include "molecule/elements.h"
#include "molecule/analysis.h"
#include "molecule/molset.h"
#include "molecule/serialize.h"
#include "molecule/combine.h"
#include "fileio/registry.h"
#include "fileio/load.h"
#include "fileio/write.h"
#include "image/image.h"
#include "imd/imd.h"
#ifdef MS_HAVE_OPENCL
#include "cl/cl.h"          /* only built with OpenCL */
#endif
/* core */
#include "ss/ss.h"
#include "select/select.h"
#include "measure/measure.h"
#include "pbc/pbc.h"
#include "surf/qsurf.h"
#include "parallel/parallel.h"
#include "movie/movie.h"
#include "scene/displaylist.h"
#include "scene/color.h"
#include "scene/material.h"
#include "scene/graphics.h"
#include "scene/scene.h"
#include "scene/lod.h"
/* reps */
#include "rep/rep.h"
/* devices */
#include "render/render.h"
#include "render/export.h"
#include "gl/gl.h"
#include "rt/rt.h"
#include "oclrt/oclrt.h"
/* assembly */
#include "assemble/world.h"
#include "assemble/view.h"
#include "assemble/devices.h"
/* Tcl bindings */
#include "app/app.h"
#include "app/options.h"
#include "app/shell.h"
#include "commands/args.h"
#include "commands/commands.h"
#include "commands/atomsel.h"
#include "commands/scenecmds.h"
#include "live/live.h"
#include "python/python.h"

#endif
