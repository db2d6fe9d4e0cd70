/* molscope.h: the map of molscope's source. Each module has one header with its public API;
 * this one includes them in pipeline order, so a reader can start here.
 *
 *   base/       utilities: errors, interned strings, worker threads
 *   molecule/   the Molecule (atoms, bonds, frames), structure analysis, the molecule set
 *   fileio/     the plugin registry, loading files into molecules, writing them out
 *   scene/      display lists, colours, materials, user graphics, the Scene devices draw
 *   view/       camera and display settings, lights, axes, stage, rotate/translate/scale
 *   render/     the render devices by VMD name and the file exporters (Tachyon, POV3, OBJ)
 *   rt/         TachyonInternal: the photorealistic CPU ray tracer on Embree
 *   commands/   the Tcl command bindings (mol, molinfo, animate, vmdinfo, ...)
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
#include "fileio/registry.h"
#include "fileio/load.h"
#include "fileio/write.h"
#include "scene/mat4.h"
#include "scene/displaylist.h"
#include "scene/color.h"
#include "scene/material.h"
#include "scene/graphics.h"
#include "scene/scene.h"
#include "view/view.h"
#include "render/render.h"
#include "rt/rt.h"
#include "app/app.h"
#include "commands/commands.h"

#endif
