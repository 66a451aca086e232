# CMake glue only: turns Debian 12 system packages into targets. No copied source lives here.
find_package(Threads REQUIRED)
find_package(glm CONFIG REQUIRED)            # libglm-dev
find_package(CLI11 CONFIG REQUIRED)          # libcli11-dev
find_package(tinyobjloader CONFIG REQUIRED)  # libtinyobjloader-dev
find_package(tinyexr CONFIG REQUIRED)        # libtinyexr-dev
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
