# heightpack_add_material(<target> <manifest.toml> OUTPUT_DIR <dir> [JOBS <n>] [ALL])
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
function(heightpack_add_material target manifest)
  cmake_parse_arguments(PARSE_ARGV 2 HP "ALL" "OUTPUT_DIR;JOBS" "")
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
