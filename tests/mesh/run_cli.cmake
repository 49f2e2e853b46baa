# One nanobake command-line scenario per CASE; fails with a message on any unexpected result.
# Inputs: NANOBAKE (the binary), CASE, WORK (a scratch directory, recreated).
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")

function(run expected_rc)
  execute_process(COMMAND "${NANOBAKE}" ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc STREQUAL "${expected_rc}")
    message(FATAL_ERROR "nanobake ${ARGN}: exit ${rc}, expected ${expected_rc}\nstdout:\n${out}\nstderr:\n${err}")
  endif()
  set(out "${out}" PARENT_SCOPE)
  set(err "${err}" PARENT_SCOPE)
endfunction()

function(expect_match text regex)
  if(NOT text MATCHES "${regex}")
    message(FATAL_ERROR "expected /${regex}/ in:\n${text}")
  endif()
endfunction()

function(expect_empty_dir_but dir only)
  file(GLOB left RELATIVE "${dir}" "${dir}/*")
  if(NOT left STREQUAL "${only}")
    message(FATAL_ERROR "expected only ${only} in ${dir}, found: ${left}")
  endif()
endfunction()

function(expect_empty_dir dir)
  file(GLOB left "${dir}/*")
  if(left)
    message(FATAL_ERROR "expected nothing in ${dir}, found: ${left}")
  endif()
endfunction()

if(CASE STREQUAL "make_and_check_sphere")
  run(0 make-mesh sphere -o "${WORK}/virion.obj" --radius 450)
  if(NOT EXISTS "${WORK}/virion.obj")
    message(FATAL_ERROR "make-mesh reported success but wrote no file")
  endif()
  run(0 check-mesh "${WORK}/virion.obj")
  expect_match("${out}" "closed yes, manifold yes, oriented yes, outward yes")
  expect_match("${out}" "\nusable\n")

elseif(CASE STREQUAL "make_and_check_rbc_json")
  run(0 make-mesh rbc --triangles 2000 -o "${WORK}/rbc.obj")
  run(0 check-mesh "${WORK}/rbc.obj" --json --tile-size 2000)
  string(JSON usable GET "${out}" usable)
  string(JSON triangles GET "${out}" triangles)
  string(JSON problems LENGTH "${out}" problems)
  string(JSON width GET "${out}" replication_area 0)
  if(NOT usable OR NOT problems EQUAL 0 OR triangles LESS 1500 OR triangles GREATER 2500 OR width LESS 2)
    message(FATAL_ERROR "unexpected report:\n${out}")
  endif()

elseif(CASE STREQUAL "check_membrane_fit")
  # A unit cube: at 150 Å rounding its 90° creases for a 40 Å bilayer would take half its area; the
  # size it names is checked; at 400 Å it fits, remeshed, and --write-prepared writes that mesh.
  file(WRITE "${WORK}/cube.obj" "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
             "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n")
  run(1 check-mesh "${WORK}/cube.obj" --diameter 150 --bilayer 40 --write-prepared "${WORK}/small.obj")
  expect_match("${out}" "cube.obj:compartment 'check-mesh' membrane: 1 place where a bilayer 40.0 Å thick cannot follow the surface")
  expect_match("${out}" "the whole mesh: rounding its creases for the bilayer takes")
  expect_match("${out}" "would take the bilayer at \"diameter\": [0-9]+ Å or more \\(checked: at that size it fits\\)")
  expect_empty_dir_but("${WORK}" "cube.obj")
  run(0 check-mesh "${WORK}/cube.obj" --diameter 400 --bilayer 40 --write-prepared "${WORK}/prepared.obj")
  expect_match("${out}" "remeshed \\(neighbouring faces turn by up to 90.0°")
  expect_match("${out}" "a bilayer 40.0 Å thick fits")
  run(0 check-mesh "${WORK}/prepared.obj")  # as the shells get it: remeshed and charted by the baker
  expect_match("${out}" "closed yes, manifold yes, oriented yes, outward yes")
  expect_match("${out}" "usable")
  run(108 check-mesh "${WORK}/cube.obj" --diameter 400 --scale 2)  # CLI11: an option excludes another
  expect_match("${err}" "--diameter excludes --scale")

elseif(CASE STREQUAL "check_without_uvs")
  file(WRITE "${WORK}/tet.obj" "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n")
  run(1 check-mesh "${WORK}/tet.obj")
  expect_match("${out}" "tet.obj:mesh: no UVs")
  expect_match("${out}" "NOT usable: 1 problem")
  run(1 check-mesh "${WORK}/tet.obj" --json)
  string(JSON rule GET "${out}" problems 0 rule)
  string(JSON usable GET "${out}" usable)
  if(NOT rule STREQUAL "no UVs" OR usable)
    message(FATAL_ERROR "unexpected report:\n${out}")
  endif()
  # What a scene would get: the baker's charts, the tetrahedron's faces in pairs.
  expect_match("${out}" "\"baker_charts\"")
  string(JSON charts GET "${out}" baker_charts charts)
  if(NOT charts EQUAL 2)
    message(FATAL_ERROR "expected 2 charts (faces pair up within 60° of their mean):\n${out}")
  endif()

elseif(CASE STREQUAL "make_uvs")
  # A closed mesh without UVs gets the baker's charts, passes, and is written with them.
  file(WRITE "${WORK}/tet.off" "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n3 2 0 3\n")
  run(0 check-mesh "${WORK}/tet.off" --make-uvs "${WORK}/charted.obj")
  expect_match("${out}" "the baker made UVs: 2 charts")
  file(STRINGS "${WORK}/charted.obj" uv_lines REGEX "^vt ")
  list(LENGTH uv_lines uv_count)
  if(NOT uv_count EQUAL 8)
    message(FATAL_ERROR "expected 8 UVs in charted.obj (two charts of two triangles), found ${uv_count}")
  endif()
  run(0 check-mesh "${WORK}/charted.obj")
  # A surface with a hole gets no charts and no file.
  file(WRITE "${WORK}/open.off" "OFF\n4 3 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n")
  run(1 check-mesh "${WORK}/open.off" --make-uvs "${WORK}/open.obj")
  expect_match("${out}" "border edge")
  if(EXISTS "${WORK}/open.obj")
    message(FATAL_ERROR "open.obj written for a mesh with a hole")
  endif()

elseif(CASE STREQUAL "check_missing_file")
  run(1 check-mesh "${WORK}/absent.obj")
  expect_match("${err}" "nanobake: error: .*absent.obj: no such file")

elseif(CASE STREQUAL "check_garbled")
  file(WRITE "${WORK}/garbled.obj" "%PDF-1.4 this is not a mesh\nf 1 2 3\n")
  run(1 check-mesh "${WORK}/garbled.obj")
  expect_match("${err}" "nanobake: error: .*garbled.obj:line 2, face 0: references a vertex that does not exist")

elseif(CASE STREQUAL "unwritable_output")
  # Parent is a regular file, then a missing directory: an error naming the path, nothing left.
  file(WRITE "${WORK}/plain_file" "x")
  run(1 make-mesh rbc -o "${WORK}/plain_file/rbc.obj")
  expect_match("${err}" "nanobake: error: .*plain_file/rbc.obj")
  run(1 make-mesh sphere -o "${WORK}/missing_dir/s.obj")
  expect_match("${err}" "nanobake: error: .*missing_dir/s.obj")
  file(REMOVE "${WORK}/plain_file")
  expect_empty_dir("${WORK}")

elseif(CASE STREQUAL "bad_arguments")
  run(1 make-mesh sphere --triangles 10 -o "${WORK}/s.obj")
  expect_match("${err}" "--triangles: a cube-sphere needs at least 48 triangles")
  run(1 make-mesh rbc --radius 3 -o "${WORK}/r.obj")
  expect_match("${err}" "--radius")
  # --remesh is read where its name is known: refused before any mesh is read.
  run(1 check-mesh "${WORK}/none.obj" --diameter 400 --remesh fast)
  expect_match("${err}" "nanobake: error: --remesh: expected auto, off or an edge in Å > 0, got 'fast'")
  run(1 check-mesh "${WORK}/none.obj" --diameter 400 --remesh=-5)
  expect_match("${err}" "nanobake: error: --remesh: expected auto, off or an edge in Å > 0, got '-5'")
  expect_empty_dir("${WORK}")

elseif(CASE STREQUAL "check_repair_refused")
  # An octahedron with a fin (a third face on one edge): "repair" will not guess which faces belong
  # together, and says so from the mesh file and the compartment, naming the edge and its faces.
  file(WRITE "${WORK}/fin.obj" "v 1 0 0\nv 0 1 0\nv -1 0 0\nv 0 -1 0\nv 0 0 1\nv 0 0 -1\nv 2 2 2\n"
             "f 1 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\nf 2 1 6\nf 3 2 6\nf 4 3 6\nf 1 4 6\nf 1 2 7\n")
  run(1 check-mesh "${WORK}/fin.obj" --diameter 1000 --repair)
  expect_match("${out}" "fin.obj:compartment 'check-mesh': cannot repair: 3 faces \\(triangles 0, 4, 8\\) share the edge between vertex 0")
  expect_empty_dir_but("${WORK}" "fin.obj")

else()
  message(FATAL_ERROR "unknown CASE ${CASE}")
endif()
