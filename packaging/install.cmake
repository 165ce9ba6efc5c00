# Installing Velvet as a desktop application (issue 17, item 16), freedesktop layout:
#   bin/velvet                                    the editor and the CLI
#   lib/velvet/velvet-image-codec.so              OpenImageIO's side, loaded on first use
#   share/velvet/resources/                       shaders, schemas, presets, HDRIs, OCIO config;
#                                                 app/resource_root.cpp finds them from the binary
#                                                 (bin/../share/velvet/resources), so the tree can
#                                                 be moved anywhere (DESTDIR, another prefix)
#   share/applications/velvet.desktop             Desktop Entry Specification 1.5
#   share/icons/hicolor/scalable/apps/velvet.svg  Icon Theme Specification, scalable size
# and a Debian package through CPack (make package), its library dependencies computed by
# dpkg-shlibdeps from the installed binary.
include(GNUInstallDirs)

install(TARGETS velvet RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
# OpenImageIO's module, loaded on first use from bin/../LIBDIR/velvet (core/image_codec.h).
if(TARGET velvet_image_codec)
  install(TARGETS velvet_image_codec LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}/velvet)
endif()
install(DIRECTORY ${CMAKE_SOURCE_DIR}/resources/
  DESTINATION ${CMAKE_INSTALL_DATADIR}/velvet/resources)
install(FILES ${CMAKE_CURRENT_LIST_DIR}/velvet.desktop DESTINATION ${CMAKE_INSTALL_DATADIR}/applications)
install(FILES ${CMAKE_CURRENT_LIST_DIR}/velvet.svg DESTINATION ${CMAKE_INSTALL_DATADIR}/icons/hicolor/scalable/apps)
install(FILES ${CMAKE_SOURCE_DIR}/resources/hdri/LICENSE.txt
  DESTINATION ${CMAKE_INSTALL_DATADIR}/doc/velvet RENAME copyright-hdri)

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME velvet)
set(CPACK_PACKAGE_VENDOR "Velvet")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
  "Physically based material editor with a deferred OpenGL viewport and a headless CLI")
set(CPACK_PACKAGE_CONTACT "Velvet maintainers <velvet@localhost>")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT) # velvet_VERSION_ARCH.deb
set(CPACK_DEBIAN_PACKAGE_SECTION graphics)
set(CPACK_STRIP_FILES ON) # the package carries no debug symbols
# Depends: from the ELF's NEEDED libraries (Qt 6, OpenImageIO, OpenColorIO, Assimp, epoxy).
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# libepoxy opens libEGL / libGL with dlopen, so they are not among the NEEDED libraries: named here
# (CPack joins this list and the computed one).
set(CPACK_DEBIAN_PACKAGE_DEPENDS "libegl1, libgl1")
# The GL driver is loaded at run time (libglvnd), not linked: Mesa's covers machines without a
# vendor driver, llvmpipe included.
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "libgl1-mesa-dri, libegl-mesa0")
include(CPack)
