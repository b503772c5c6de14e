# Installs the build at BUILD_DIR, moves the installed folder to WORK_DIR/prefix, then configures, builds
# and runs the consumers against it, and checks that the water material is rebuilt exactly when its map's
# bytes change (Ninja + depfile). Then embeds heightpack's source with add_subdirectory.
file(REMOVE_RECURSE ${WORK_DIR})
macro(run)
  execute_process(COMMAND ${ARGV} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGV}\n${out}\n${err}")
  endif()
endmacro()
set(src ${WORK_DIR}/src)
set(build ${WORK_DIR}/build)
set(texture ${build}/water/chop.exr)
file(COPY ${SOURCE_DIR}/ DESTINATION ${src})
file(COPY_FILE ${EXAMPLES_DIR}/maps/choppy.png ${src}/water/chop.png)

# Installed into one folder, then moved to another: the package must hold no path of where it was
# installed nor of the libraries on the machine that built it (it finds them again where it is used).
run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${WORK_DIR}/installed)
file(RENAME ${WORK_DIR}/installed ${WORK_DIR}/prefix)
file(GLOB_RECURSE package_files ${WORK_DIR}/prefix/lib/cmake/heightpack/*.cmake)
foreach(f IN LISTS package_files)
  file(READ ${f} text)
  foreach(absolute ${WORK_DIR}/installed ${BUILD_DIR} libopencv_core.so libxxhash.so libdeflate.so libzstd.so)
    string(FIND "${text}" "${absolute}" at)
    if(at GREATER_EQUAL 0)
      message(FATAL_ERROR "${f} names ${absolute}: the installed package cannot move")
    endif()
  endforeach()
endforeach()
# Every manifest error points at the manifest reference: the installed program, moved with its prefix,
# names the copy installed with it, and that file is there.
file(WRITE ${WORK_DIR}/misspelt.toml "format = 1\nname = \"sea\"\n\n[[displacement]]\nname = \"chop\"\n"
                                     "sorce = \"chop.png\"\ntile_size = 16.0\n")
execute_process(COMMAND ${WORK_DIR}/prefix/bin/heightpack build ${WORK_DIR}/misspelt.toml --check-only
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 3 OR NOT err MATCHES "unknown key 'displacement\\[0\\]\\.sorce'.*did you mean 'source'\\? see (.+) for every key\\)")
  message(FATAL_ERROR "a misspelt key did not name the reference with a suggestion (${rc}):\n${err}")
endif()
set(reference "${CMAKE_MATCH_1}")
file(REAL_PATH ${WORK_DIR}/prefix/share/doc/heightpack/manifest.md installed_reference)
if(NOT EXISTS "${reference}" OR NOT reference STREQUAL installed_reference)
  message(FATAL_ERROR "the manifest error names ${reference}, not the installed ${installed_reference}:\n${err}")
endif()

# The man pages and bash completion (tools/manual): a page for the program and for each command its
# --help lists, and the completion where bash-completion looks for it by the program's name; the same
# for the viewer when it was built (none of it in a build configured with HEIGHTPACK_BUILD_MANUAL=OFF).
if(MANUAL)
  execute_process(COMMAND ${WORK_DIR}/prefix/bin/heightpack --help OUTPUT_VARIABLE help RESULT_VARIABLE rc)
  string(REGEX MATCH "Subcommands:\n([^\n]+\n)+" subcommands "${help}")  # up to the blank line
  string(REGEX MATCHALL "\n  [a-z]+" commands "${subcommands}")
  set(expected heightpack)
  foreach(command IN LISTS commands)
    string(STRIP "${command}" command)
    list(APPEND expected heightpack-${command})
  endforeach()
  list(LENGTH expected pages)
  if(NOT rc EQUAL 0 OR pages LESS 3)
    message(FATAL_ERROR "the installed heightpack --help lists no commands (${rc}):\n${help}")
  endif()
  set(programs heightpack)
  if(EXISTS ${WORK_DIR}/prefix/bin/heightpack-view)
    list(APPEND expected heightpack-view)
    list(APPEND programs heightpack-view)
  endif()
  foreach(page IN LISTS expected)
    if(NOT EXISTS ${WORK_DIR}/prefix/share/man/man1/${page}.1)
      message(FATAL_ERROR "cmake --install put no man page share/man/man1/${page}.1")
    endif()
  endforeach()
  foreach(program IN LISTS programs)
    if(NOT EXISTS ${WORK_DIR}/prefix/share/bash-completion/completions/${program})
      message(FATAL_ERROR "cmake --install put no bash completion share/bash-completion/completions/${program}")
    endif()
  endforeach()
endif()

# A pure asset project (LANGUAGES NONE: no compiler) finds the package and builds a material with it;
# asking it for a library instead says that the libraries need C++.
set(assets_build ${WORK_DIR}/assets_build)
run(${CMAKE_COMMAND} -S ${src}/assets_only -B ${assets_build} -G Ninja -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix)
run(${CMAKE_COMMAND} --build ${assets_build})
if(NOT EXISTS ${assets_build}/water/material.json OR NOT EXISTS ${assets_build}/water/chop.exr)
  message(FATAL_ERROR "the asset project without a compiler did not build its water material:\n${out}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -S ${src}/assets_only -B ${WORK_DIR}/assets_core_build -G Ninja
                        -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix -DHEIGHTPACK_COMPONENTS=core
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(rc EQUAL 0 OR NOT err MATCHES "are C\\+\\+: enable CXX")
  message(FATAL_ERROR "asking for heightpack::core without C++ did not say it needs C++ (${rc}):\n${out}\n${err}")
endif()

# heightpack::core alone: configured, built (with image and TOML library headers poisoned) and run, and it
# links no image or TOML library.
set(core_build ${WORK_DIR}/core_build)
run(${CMAKE_COMMAND} -S ${src}/core_only -B ${core_build} -G Ninja -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix)
run(${CMAKE_COMMAND} --build ${core_build} --verbose)
foreach(library OpenImageIO OpenEXR Iex Imath tomlplusplus deflate xxhash)
  if(out MATCHES "${library}")
    message(FATAL_ERROR "linking heightpack::core alone named ${library}:\n${out}")
  endif()
endforeach()
run(${core_build}/core_consumer)
message(STATUS "${out}")
execute_process(COMMAND ldd ${core_build}/core_consumer OUTPUT_VARIABLE needed)
foreach(library OpenImageIO OpenEXR tomlplusplus)
  if(needed MATCHES "${library}")
    message(FATAL_ERROR "core_consumer loads ${library}:\n${needed}")
  endif()
endforeach()

run(${CMAKE_COMMAND} -S ${src} -B ${build} -G Ninja -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix)
run(${CMAKE_COMMAND} --build ${build})
run(${build}/consumer)
if(NOT EXISTS ${build}/water/material.json OR NOT EXISTS ${texture})
  message(FATAL_ERROR "the water material was not built")
endif()
file(SHA256 ${texture} first)
# The same material through its plan (PER_OUTPUT): one command per output, the same bytes.
macro(expect_same_as_actions)
  foreach(name chop.exr material.json)
    file(SHA256 ${build}/water/${name} whole)
    file(SHA256 ${build}/water_actions/${name} per_output)
    if(NOT whole STREQUAL per_output)
      message(FATAL_ERROR "water_actions/${name} differs from water/${name}: the plan's commands made other bytes")
    endif()
  endforeach()
endmacro()
expect_same_as_actions()

# Nothing changed: Ninja has nothing to do.
run(${CMAKE_COMMAND} --build ${build})
if(NOT out MATCHES "no work to do")
  message(FATAL_ERROR "a second build did work:\n${out}")
endif()

# The map touched, its bytes the same: Ninja re-runs heightpack (the depfile names the map), which
# rebuilds nothing; then Ninja is satisfied again.
file(TOUCH ${src}/water/chop.png)
run(${CMAKE_COMMAND} --build ${build})
if(NOT out MATCHES "building water material")
  message(FATAL_ERROR "touching the map did not re-run heightpack build:\n${out}")
endif()
file(SHA256 ${texture} touched)
if(NOT touched STREQUAL first)
  message(FATAL_ERROR "the texture changed though the map did not")
endif()
run(${CMAKE_COMMAND} --build ${build})
if(NOT out MATCHES "no work to do")
  message(FATAL_ERROR "the build after a touch was not up to date:\n${out}")
endif()

# The map changed: the texture is rebuilt from it.
file(COPY_FILE ${EXAMPLES_DIR}/maps/ripple.png ${src}/water/chop.png)
run(${CMAKE_COMMAND} --build ${build})
file(SHA256 ${texture} changed)
if(changed STREQUAL first)
  message(FATAL_ERROR "changing the map did not rebuild its texture")
endif()
expect_same_as_actions()
message(STATUS "consumer: installed package, heightpack_add_material and its depfile work")

# heightpack's source embedded with add_subdirectory: only what the engine links is built.
set(embedded_build ${WORK_DIR}/embedded_build)
run(${CMAKE_COMMAND} -S ${src}/embedded -B ${embedded_build} -G Ninja -DHEIGHTPACK_SOURCE_DIR=${HEIGHTPACK_SOURCE_DIR})
run(${CMAKE_COMMAND} --build ${embedded_build} --target embedded_consumer)
run(${embedded_build}/embedded_consumer)
message(STATUS "embedded: ${out}")
