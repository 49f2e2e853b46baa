# The Python interpreter tests and benchmarks run (their scripts and inline checks), found by CMake
# rather than assumed at one path: ${Python3_EXECUTABLE} and Python3::Interpreter.
#
# Several tests need numpy and gemmi, which scripts/setup.sh installs for the system's python3
# (python3-numpy, python3-gemmi). The first python3 on PATH may be another one without them (pyenv,
# a virtualenv), so every python3 on the search path is tried in order and the first that imports
# both is used; -DPython3_EXECUTABLE=<path> chooses one by hand.
function(nano_python_has_test_modules result candidate)
  execute_process(COMMAND "${candidate}" -c "import numpy, gemmi" RESULT_VARIABLE status OUTPUT_QUIET ERROR_QUIET)
  if(NOT status EQUAL 0)
    set(${result} FALSE PARENT_SCOPE)
  endif()
endfunction()

if(NOT Python3_EXECUTABLE)
  find_program(NANO_PYTHON3 NAMES python3 NAMES_PER_DIR VALIDATOR nano_python_has_test_modules
               DOC "a python3 that imports numpy and gemmi (the tests need them)")
  if(NANO_PYTHON3)
    set(Python3_EXECUTABLE "${NANO_PYTHON3}")
  endif()
endif()
find_package(Python3 COMPONENTS Interpreter REQUIRED)

if(NANO_BUILD_TESTS)
  set(has_modules TRUE)
  nano_python_has_test_modules(has_modules "${Python3_EXECUTABLE}")
  if(has_modules)
    message(STATUS "Python for the tests: ${Python3_EXECUTABLE} (numpy and gemmi import)")
  else()
    message(WARNING "No python3 found that imports numpy and gemmi; the tests use ${Python3_EXECUTABLE} and those "
                    "that need numpy or gemmi will fail. Install them (scripts/setup.sh: python3-numpy, "
                    "python3-gemmi) or pass -DPython3_EXECUTABLE=<a python3 that has them>.")
  endif()
endif()
