# Helpers that turn a folder of sources into targets, so adding a test, benchmark or example
# means adding a file, not editing CMake.

# Link what a source needs: cosmpm, plus cosmpm::hdf5 when the source, or a header next to it,
# includes an HDF5 header of cosmpm (io/hdf5*.hpp, io/checkpoint.hpp).
function(cosmpm_link_project_target target)
  target_link_libraries(${target} PRIVATE cosmpm::cosmpm cosmpm_project_options)
  get_target_property(_sources ${target} SOURCES)
  set(_headers)
  foreach(_source IN LISTS _sources)
    get_filename_component(_dir "${_source}" DIRECTORY)
    file(GLOB _local_headers "${_dir}/*.hpp")
    list(APPEND _headers ${_local_headers})
  endforeach()
  list(REMOVE_DUPLICATES _headers)
  foreach(_source IN LISTS _sources _headers)
    file(READ "${_source}" _text)
    if(_text MATCHES "cosmpm/io/hdf5" OR _text MATCHES "cosmpm/io/checkpoint")
      if(NOT COSMPM_HAVE_HDF5)
        message(FATAL_ERROR "${_source} needs HDF5 but HDF5 was not found")
      endif()
      target_link_libraries(${target} PRIVATE cosmpm::hdf5)
      break()
    endif()
  endforeach()
endfunction()
