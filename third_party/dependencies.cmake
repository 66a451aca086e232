# CMake glue only: turns Debian 12 system packages into targets. No copied source lives here.
find_package(Threads REQUIRED)
find_package(glm CONFIG REQUIRED)            # libglm-dev
find_package(CLI11 CONFIG REQUIRED)          # libcli11-dev
find_package(tinyobjloader CONFIG REQUIRED)  # libtinyobjloader-dev
find_package(tinyexr CONFIG REQUIRED)        # libtinyexr-dev
find_package(nlohmann_json 3 CONFIG REQUIRED)  # nlohmann-json3-dev: lueur-bench's JSON
find_package(embree 3 CONFIG QUIET)         # libembree-dev, optional: the second accelerator back-end
find_package(PkgConfig REQUIRED)
pkg_check_modules(STB REQUIRED IMPORTED_TARGET stb)   # libstb-dev (stb_image_write is compiled into libstb)

add_library(lueur::tinyobjloader INTERFACE IMPORTED)
target_link_libraries(lueur::tinyobjloader INTERFACE tinyobjloader::tinyobjloader)
add_library(lueur::tinyexr INTERFACE IMPORTED)
target_link_libraries(lueur::tinyexr INTERFACE tinyexr::tinyexr)
add_library(lueur::stb INTERFACE IMPORTED)
target_link_libraries(lueur::stb INTERFACE PkgConfig::STB)
