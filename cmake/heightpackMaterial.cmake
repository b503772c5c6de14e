# heightpack_add_material(<target> <manifest.toml> OUTPUT_DIR <dir> [JOBS <n>] [ALL] [PER_OUTPUT])
#
# Adds <target>, which runs `heightpack build <manifest> -o <dir>` when the manifest, any map it reads
# or heightpack itself changed. The maps are learned from the depfile the build writes (Make and Ninja
# read it), so adding a map to the manifest needs no change here. The build itself is incremental by
# content hash: a map touched but not changed rebuilds nothing.
#
#   find_package(heightpack CONFIG REQUIRED)
#   heightpack_add_material(ocean_water water/ocean.toml OUTPUT_DIR ${CMAKE_BINARY_DIR}/water/ocean ALL)
#   add_dependencies(game ocean_water)
#
# OUTPUT_DIR is relative to the current binary folder; the manifest to the current source folder.
# After the call, the target's HEIGHTPACK_MATERIAL_JSON property holds the material.json path.
#
# PER_OUTPUT imports the build's own plan (`heightpack build --plan json`, run when CMake configures and
# again whenever the manifest changes): one custom command per output file (each frame and cascade of a
# synthesised sea) and one for material.json, so the engine's build (Ninja, a farm) runs them side by side
# and reruns only what a changed map feeds. It needs an installed heightpack (find_package), whose program
# exists when CMake configures.
function(heightpack_add_material target manifest)
  cmake_parse_arguments(PARSE_ARGV 2 HP "ALL;PER_OUTPUT" "OUTPUT_DIR;JOBS" "")
  if(NOT HP_OUTPUT_DIR)
    message(FATAL_ERROR "heightpack_add_material(${target}): OUTPUT_DIR is required")
  endif()
  if(HP_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "heightpack_add_material(${target}): unknown arguments ${HP_UNPARSED_ARGUMENTS}")
  endif()
  if(NOT HP_JOBS)
    set(HP_JOBS 1)
  endif()
  if(TARGET heightpack::heightpack)
    set(exe heightpack::heightpack)
  elseif(TARGET heightpack)
    set(exe heightpack)  # inside heightpack's own build
  else()
    message(FATAL_ERROR "heightpack_add_material: no heightpack executable target; call find_package(heightpack) first")
  endif()

  get_filename_component(manifest "${manifest}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_SOURCE_DIR}")
  get_filename_component(output "${HP_OUTPUT_DIR}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_BINARY_DIR}")
  set(stamp "${CMAKE_CURRENT_BINARY_DIR}/${target}.heightpack-stamp")
  set(depfile "${CMAKE_CURRENT_BINARY_DIR}/${target}.heightpack.d")
  set(all "")
  if(HP_ALL)
    set(all ALL)
  endif()

  if(HP_PER_OUTPUT)
    _heightpack_add_material_actions(${target} "${exe}" "${manifest}" "${output}" "${all}")
    return()
  endif()

  add_custom_command(
    OUTPUT "${stamp}"
    BYPRODUCTS "${output}/material.json"
    COMMAND ${exe} build "${manifest}" -o "${output}" --jobs ${HP_JOBS} --quiet --depfile "${depfile}" --stamp "${stamp}"
    DEPENDS "${manifest}" "$<TARGET_FILE:${exe}>"
    DEPFILE "${depfile}"
    COMMENT "heightpack: building water material ${target}"
    VERBATIM)
  add_custom_target(${target} ${all} DEPENDS "${stamp}")
  set_target_properties(${target} PROPERTIES HEIGHTPACK_MATERIAL_JSON "${output}/material.json")
endfunction()

# One custom command per action of the build's plan (see PER_OUTPUT above).
function(_heightpack_add_material_actions target exe manifest output all)
  get_target_property(imported ${exe} IMPORTED)
  if(NOT imported)
    message(FATAL_ERROR "heightpack_add_material(${target} PER_OUTPUT): needs an installed heightpack "
                        "(find_package), whose program exists when CMake configures")
  endif()
  get_target_property(program ${exe} LOCATION)
  execute_process(COMMAND "${program}" build "${manifest}" -o "${output}" --plan json
                  RESULT_VARIABLE rc OUTPUT_VARIABLE plan ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "heightpack_add_material(${target}): ${err}")
  endif()
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS "${manifest}")
  string(JSON count LENGTH "${plan}" actions)
  math(EXPR last "${count} - 1")
  set(made "")
  foreach(a RANGE ${last})
    foreach(part command inputs outputs)
      set(${part} "")
      string(JSON n LENGTH "${plan}" actions ${a} ${part})
      math(EXPR n_last "${n} - 1")
      foreach(i RANGE ${n_last})
        string(JSON item GET "${plan}" actions ${a} ${part} ${i})
        list(APPEND ${part} "${item}")
      endforeach()
    endforeach()
    string(JSON description GET "${plan}" actions ${a} description)
    add_custom_command(OUTPUT ${outputs} COMMAND ${command} DEPENDS ${inputs} COMMENT "heightpack: ${description}" VERBATIM)
    list(APPEND made ${outputs})
  endforeach()
  add_custom_target(${target} ${all} DEPENDS ${made})
  set_target_properties(${target} PROPERTIES HEIGHTPACK_MATERIAL_JSON "${output}/material.json")
endfunction()
