# stochtex_add_method(NAME <name> RUNTIME <file>... ANALYSIS <file>... GL <file>... GLSL <file>...)
# Declares the files of one method folder, src/methods/<name>/, from that folder's CMakeLists.txt
# (docs/design.md §11), so that the folder says which library compiles each of its files:
#   RUNTIME   the model, its file I/O and its CPU evaluators (scalar and vectorised): stochtex::runtime
#   ANALYSIS  what builds the model: stochtex::analysis
#   GL        the GPU twin's data packing and render pass: stochtex::gl (when STOCHTEX_BUILD_GL)
#   GLSL      the GPU twin's shaders, embedded into stochtex::gl
# The folder's analysis.hpp (the registry's) and gl_twin.hpp (the GPU backend's) are taken by
# name. Every .cpp and .glsl file of the folder must be in one list: a file in none would be
# compiled by no library, so configuring stops there. The top-level CMakeLists.txt collects the
# lists (the global properties STOCHTEX_METHOD_*) before it defines the libraries.
function(stochtex_add_method)
  cmake_parse_arguments(METHOD "" "NAME" "RUNTIME;ANALYSIS;GL;GLSL" ${ARGN})
  set(folder ${CMAKE_CURRENT_SOURCE_DIR})
  get_filename_component(folder_name ${folder} NAME)
  if(NOT METHOD_NAME STREQUAL folder_name)
    message(FATAL_ERROR "stochtex_add_method(NAME ${METHOD_NAME}) is called from ${folder}")
  endif()
  if(METHOD_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "stochtex_add_method(${METHOD_NAME}): unknown arguments ${METHOD_UNPARSED_ARGUMENTS}")
  endif()
  set(declared "")
  foreach(kind RUNTIME ANALYSIS GL GLSL)
    set(paths "")
    foreach(file IN LISTS METHOD_${kind})
      if(NOT EXISTS ${folder}/${file})
        message(FATAL_ERROR "stochtex_add_method(${METHOD_NAME}): ${folder}/${file} does not exist")
      endif()
      list(APPEND paths ${folder}/${file})
    endforeach()
    list(APPEND declared ${paths})
    set_property(GLOBAL APPEND PROPERTY STOCHTEX_METHOD_${kind} ${paths})
  endforeach()
  foreach(header analysis.hpp gl_twin.hpp)
    if(NOT EXISTS ${folder}/${header})
      message(FATAL_ERROR "stochtex_add_method(${METHOD_NAME}): every method has ${header}")
    endif()
  endforeach()
  set_property(GLOBAL APPEND PROPERTY STOCHTEX_METHOD_ANALYSIS_HEADERS ${folder}/analysis.hpp)
  set_property(GLOBAL APPEND PROPERTY STOCHTEX_METHOD_GL_TWINS ${folder}/gl_twin.hpp)
  file(GLOB present CONFIGURE_DEPENDS ${folder}/*.cpp ${folder}/*.glsl)
  if(declared)
    list(REMOVE_ITEM present ${declared})
  endif()
  if(present)
    message(FATAL_ERROR "stochtex_add_method(${METHOD_NAME}): ${present} is in none of RUNTIME, "
                        "ANALYSIS, GL and GLSL, so no library would compile it")
  endif()
endfunction()
