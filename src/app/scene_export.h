// --export-scene: the scene as Lueur renders it, written as OBJ + MTL for another renderer (or a later run) to read.
#pragma once

#include "app/options.h"

namespace lueur {

/// Refuses (IoError, one line) an export path that is not a .obj file in a writable directory, before anything is
/// loaded or written: the OBJ and its MTL are written one after the other, and neither may be left alone.
void check_export_path(const std::string& obj_path);

/// Opens the scene the options name (or the default one) as a render would, with its computed shading normals and
/// the light rig it adds, writes it to options.export_scene (and its MTL beside it), prints that path on stdout and
/// on stderr the options that render the export as the scene renders (the view it opens with at the options' size,
/// and the AO radius its model's size gives). Throws SceneError, IoError.
void export_scene(const AppOptions& options);

}  // namespace lueur
