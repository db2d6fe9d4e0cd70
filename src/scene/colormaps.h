/* colormaps.h: the perceptual colour maps VMD 1.9.4 offers as colour-scale methods, each a
 * table of 256 RGB entries from 0 (low) to 1 (high), generated into colormaps.c by
 * scripts/colormaps.py from the published data. */
#ifndef MS_COLORMAPS_H
#define MS_COLORMAPS_H

extern const float ms_colormap_viridis[256][3];
extern const float ms_colormap_magma[256][3];
extern const float ms_colormap_inferno[256][3];
extern const float ms_colormap_plasma[256][3];
extern const float ms_colormap_cividis[256][3];
extern const float ms_colormap_turbo[256][3];

#endif
