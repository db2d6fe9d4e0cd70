/* molscope.h: the map of molscope's source. Each module has one header with its public API;
 * this one includes them in pipeline order, so a reader can start here.
 *
 *   base/       utilities: errors, interned strings, worker threads
 *   molecule/   the Molecule (atoms, bonds, frames), structure analysis, the molecule set,
 *               serialisation (a molecule as bytes for other ranks)
 *   ss/         secondary structure computed from the backbone (DSSP), on demand
 *   select/     the atom selection language (compiled to a tree, evaluated to bit sets) and
 *               the atomselect command
 *   fileio/     the plugin registry, loading files into molecules, writing them out
 *   scene/      display lists, colours, materials, user graphics, the Scene devices draw
 *   view/       camera and display settings, lights, axes, stage, rotate/translate/scale
 *   render/     the render devices by VMD name and the file exporters (Tachyon, POV3, OBJ)
 *   rep/        representations: selection + drawing method + colouring + material, cached
 *               display lists; one file per drawing method (lines.c ... newcartoon.c)
 *   parallel/   MPI: start-up and shutdown, collectives, the dynamic for-loop, loading a
 *               file on rank 0 and broadcasting the molecule (also the core of the
 *               molscope::parallel Tcl package, ../tcl/parallel)
 *   movie/      movies: frame files and resuming, frames handed out across ranks, the
 *               ffmpeg encoder fed in frame order, progress (the command: ../tcl/movie.tcl)
 *   surf/       QuickSurf: Gaussian density maps, marching cubes, the surface engine
 *   cl/         what the OpenCL users (surf/, oclrt/) share: errors, device choice, the
 *               per-user cache folders, programs built or read from the binary cache
 *   gl/         offscreen OpenGL (OSMesa, EGL): the display device and `render snapshot`
 *   rt/         TachyonInternal: the photorealistic CPU ray tracer on Embree
 *   live/       the live view in a browser: frames rendered at idle, a small web server
 *   commands/   the Tcl command bindings (mol, molinfo, animate, vmdinfo, ...)
 *   vecmath/    double-precision vectors, 4x4 matrices, symmetric eigen-solver
 *   measure/    the numbers behind `measure`: centers, fits, contacts, SASA, g(r) ...
 *   commands/   the Tcl command bindings (mol, molinfo, animate, measure, vecadd ...)
 *   app/        the program: command line, startup order, shell
 *   ../plugins  file formats, each a module loaded at run time (ms_plugin.h)
 */
#ifndef MOLSCOPE_H
#define MOLSCOPE_H

#include "base/base.h"
#include "base/strtab.h"
#include "base/threads.h"
#include "molecule/molecule.h"
#include "molecule/elements.h"
#include "molecule/analysis.h"
#include "molecule/molset.h"
#include "molecule/serialize.h"
#include "ss/ss.h"
#include "select/select.h"
#include "fileio/registry.h"
#include "fileio/load.h"
#include "fileio/write.h"
#include "scene/mat4.h"
#include "scene/displaylist.h"
#include "scene/color.h"
#include "scene/material.h"
#include "scene/graphics.h"
#include "scene/scene.h"
#include "assemble/view.h"
#include "render/render.h"
#include "rep/rep.h"
#include "vecmath/vecmath.h"
#include "measure/measure.h"
#include "parallel/parallel.h"
#include "movie/movie.h"
#include "surf/qsurf.h"
#include "gl/gl.h"
#include "rt/rt.h"
#include "live/live.h"
#include "app/app.h"
#include "commands/commands.h"
#include "commands/atomsel.h"

#endif
