# `cmake --install`: the shared library, the public headers, a CMake package (find_package(ssrcl)
# gives ssrcl::ssrcl) and a pkg-config file. tests/consumer/ builds against the result.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

install(TARGETS ssrcl EXPORT ssrclTargets
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/ssrcl ${PROJECT_BINARY_DIR}/include/ssrcl
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(TARGETS ssrcl_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY ${SSRCL_SAMPLES} DESTINATION ${CMAKE_INSTALL_DATADIR}/ssrcl/samples
        FILES_MATCHING PATTERN "*.exr" PATTERN "*.camera.json")

set(SSRCL_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/ssrcl)
install(EXPORT ssrclTargets NAMESPACE ssrcl:: DESTINATION ${SSRCL_CMAKE_DIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/ssrclConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/ssrclConfig.cmake INSTALL_DESTINATION ${SSRCL_CMAKE_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/ssrclConfigVersion.cmake COMPATIBILITY SameMajorVersion)
install(FILES ${PROJECT_BINARY_DIR}/ssrclConfig.cmake ${PROJECT_BINARY_DIR}/ssrclConfigVersion.cmake
        DESTINATION ${SSRCL_CMAKE_DIR})

file(RELATIVE_PATH SSRCL_PC_UP /prefix/${CMAKE_INSTALL_LIBDIR}/pkgconfig /prefix)  # "../.." or deeper
configure_file(${PROJECT_SOURCE_DIR}/cmake/ssrcl.pc.in ${PROJECT_BINARY_DIR}/ssrcl.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/ssrcl.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
