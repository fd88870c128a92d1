# The installed CMake package: find_package(ltp) gives ltp::core, ltp::openfast, ltp::models,
# ltp::integrate, ltp::floquet, ltp::hill, ltp::htf and ltp::studies.
# The targets install themselves into the export set ltpTargets (see core/, openfast/, models/,
# integrate/, floquet/, hill/, htf/).
include(CMakePackageConfigHelpers)
set(LTP_CONFIG_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/ltp)

install(EXPORT ltpTargets NAMESPACE ltp:: DESTINATION ${LTP_CONFIG_DIR})
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/ltpConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/ltpConfig.cmake
                              INSTALL_DESTINATION ${LTP_CONFIG_DIR})
# 0.x: the API may change with every minor version.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/ltpConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/ltpConfig.cmake ${PROJECT_BINARY_DIR}/ltpConfigVersion.cmake
        DESTINATION ${LTP_CONFIG_DIR})
