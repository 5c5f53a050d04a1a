# install.cmake: the workbench's desktop integration, included by src/app/CMakeLists.txt.
# The desktop entry (Exec=oit-workbench, Icon=oit-workbench) and the scalable icon go where
# freedesktop.org menus and icon themes look under the prefix. Only the SVG is installed: no
# SVG rasteriser is among the build dependencies, and hicolor's scalable size serves every size.
install(FILES ${CMAKE_CURRENT_LIST_DIR}/oit-workbench.desktop
  DESTINATION ${CMAKE_INSTALL_DATADIR}/applications)
install(FILES ${CMAKE_CURRENT_LIST_DIR}/oit-workbench.svg
  DESTINATION ${CMAKE_INSTALL_DATADIR}/icons/hicolor/scalable/apps)
# Sessions (.oitsession, docs/sessions.md): their MIME type, application/x-oit-session, for
# shared-mime-info (the desktop entry's MimeType lists it; packagers run update-mime-database).
install(FILES ${CMAKE_CURRENT_LIST_DIR}/oit-workbench-mime.xml
  DESTINATION ${CMAKE_INSTALL_DATADIR}/mime/packages RENAME oit-workbench.xml)
