// View files: the settings as JSON, saved by the window and rendered again exactly by
// `lueur --headless --view-file`. Every key is a row of the settings table; an unknown key is an error, and files
// written before the table existed still load (tests/views/). Depends on settings/ only.
#pragma once

#include <stdexcept>
#include <string>

#include "settings/settings.h"

namespace lueur {

/// A view file that cannot be used; the message names the field.
struct ViewFileError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

std::string view_to_json(const Settings& settings);
/// Parses a view; settings the file does not hold keep the values of `defaults`. Throws ViewFileError.
Settings view_from_json(const std::string& text, const Settings& defaults = {});

/// Writes atomically (IoError) / reads (IoError for a missing file, ViewFileError for bad contents).
void save_view_file(const std::string& path, const Settings& settings);
Settings load_view_file(const std::string& path, const Settings& defaults = {});

}  // namespace lueur
