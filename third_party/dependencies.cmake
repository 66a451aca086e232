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
if(LUEUR_SANITIZE OR LUEUR_FUZZ)
  # The implementation compiled here from the same Debian header, so that the sanitizers see inside it.
  add_library(lueur_tinyobjloader STATIC ${CMAKE_CURRENT_LIST_DIR}/tinyobjloader_impl.cpp)
  target_include_directories(lueur_tinyobjloader SYSTEM PUBLIC
    $<TARGET_PROPERTY:tinyobjloader::tinyobjloader,INTERFACE_INCLUDE_DIRECTORIES>)
  target_link_libraries(lueur::tinyobjloader INTERFACE lueur_tinyobjloader)
else()
  target_link_libraries(lueur::tinyobjloader INTERFACE tinyobjloader::tinyobjloader)
endif()
add_library(lueur::tinyexr INTERFACE IMPORTED)
target_link_libraries(lueur::tinyexr INTERFACE tinyexr::tinyexr)
add_library(lueur::stb INTERFACE IMPORTED)
target_link_libraries(lueur::stb INTERFACE PkgConfig::STB)

# ---- display and UI (the window, off-screen screenshots, the panel) --------
find_package(nlohmann_json 3 CONFIG REQUIRED)             # nlohmann-json3-dev
find_package(glfw3 3.3 CONFIG REQUIRED)                   # libglfw3-dev
find_package(OpenGL REQUIRED COMPONENTS OpenGL EGL)       # libgl-dev, libopengl-dev, libegl-dev (+ Mesa's libegl-mesa0)
pkg_check_modules(OSMESA REQUIRED IMPORTED_TARGET osmesa) # libosmesa6-dev
pkg_check_modules(IMGUI REQUIRED IMPORTED_TARGET imgui)   # libimgui-dev

# Debian's libimgui.a has the OpenGL 3 back-end compiled with its own loader, which dlopens libGL and so fails
# under OSMesa. Debian also ships that back-end's source: compile it here, from the system, with a custom loader
# that takes the current context's get-proc-address (src/ui/imgui_gl_loader.cpp). Nothing is copied into the repo.
set(LUEUR_IMGUI_BACKENDS /usr/share/doc/libimgui-dev/examples/backends)
find_file(LUEUR_IMGUI_OPENGL3_SOURCE imgui_impl_opengl3.cpp PATHS ${LUEUR_IMGUI_BACKENDS} NO_DEFAULT_PATH REQUIRED)
find_file(LUEUR_IMGUI_LOADER_HEADER imgui_impl_opengl3_loader.h PATH_SUFFIXES imgui/backends REQUIRED)
add_library(lueur_imgui_opengl3 STATIC ${LUEUR_IMGUI_OPENGL3_SOURCE})
target_compile_definitions(lueur_imgui_opengl3 PUBLIC IMGUI_IMPL_OPENGL_LOADER_CUSTOM)
target_compile_options(lueur_imgui_opengl3 PRIVATE -include ${LUEUR_IMGUI_LOADER_HEADER} -w)
target_include_directories(lueur_imgui_opengl3 PUBLIC ${IMGUI_INCLUDEDIR}/backends)
target_link_libraries(lueur_imgui_opengl3 PUBLIC PkgConfig::IMGUI)
