// What the passes that place points on the terrain read (kFrameWorldGlsl and
// kKeyHeightGlsl: the charts, the labels' probes): the resident blocks'
// tile table, the frame's uniforms, the view origin and the eye, bound once
// for a program here instead of in each pass.
#pragma once

#include "camera/camera.hpp"
#include "render/gl_program.hpp"
#include "render/line_renderer.hpp"
#include "render/terrain_renderer.hpp"

namespace globe::viewer {

// Fills `table_buffer` with the table of `heights`' resident blocks, binds it
// at shader storage `binding`, and sets `p`'s uniforms (p is in use after).
void bind_key_heights(const GlProgram& p, GLuint table_buffer, int binding, const View& view,
                      const WorldFrame& world, const TerrainRenderer& terrain,
                      const TerrainHeights& heights, double exaggeration);

}  // namespace globe::viewer
