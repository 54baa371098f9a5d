# A Debian package (cpack -G DEB in the build directory):
# idbench_<version>_amd64.deb with the executable, the Python module, the
# libraries, headers and CMake package. Its dependencies come from the
# shared libraries the binaries link (dpkg-shlibdeps).
install(FILES ${PROJECT_SOURCE_DIR}/cmake/debian-copyright DESTINATION ${CMAKE_INSTALL_DATAROOTDIR}/doc/idbench
        RENAME copyright)

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME idbench)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "workbench for robot excitation design and dynamic parameter identification")
set(CPACK_PACKAGE_DESCRIPTION "Designs excitation trajectories, simulates them in Bullet and identifies the masses, \
inertias and friction of serial robots from URDF files and joint logs; command line, GUI, C++ libraries and a Python module.")
set(CPACK_PACKAGE_CONTACT "The idbench developers")
set(CPACK_RESOURCE_FILE_LICENSE ${PROJECT_SOURCE_DIR}/LICENSE)
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)          # idbench_0.1.0_amd64.deb
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# The Python module needs Debian's python3 and numpy; the rest does not.
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "python3, python3-numpy")
set(CPACK_DEBIAN_COMPRESSION_TYPE gzip)
include(CPack)
