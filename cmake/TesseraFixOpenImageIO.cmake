# Debian 12's OpenImageIO config names /usr/include/opencv4, which is not
# installed; CMake refuses targets with non-existent include paths. Used by
# this build (TesseraDependencies.cmake) and by installed TesseraConfig.cmake.
if(TARGET OpenImageIO::OpenImageIO)
  foreach(prop INTERFACE_INCLUDE_DIRECTORIES INTERFACE_SYSTEM_INCLUDE_DIRECTORIES)
    get_target_property(dirs OpenImageIO::OpenImageIO ${prop})
    if(dirs)
      set(kept "")
      foreach(d IN LISTS dirs)
        if(EXISTS "${d}")
          list(APPEND kept "${d}")
        endif()
      endforeach()
      set_target_properties(OpenImageIO::OpenImageIO PROPERTIES ${prop} "${kept}")
    endif()
  endforeach()
endif()
