/* Version of the leptrino headers.
 *
 * Kept in the tree (not generated) so that the sources can be dropped into
 * any build system or IDE project. CMake checks at configure time that these
 * numbers match project(leptrino VERSION ...) in CMakeLists.txt and stops if
 * they differ: change both together. */
#ifndef LEPTRINO_VERSION_H
#define LEPTRINO_VERSION_H

#define LEP_VERSION_MAJOR 0
#define LEP_VERSION_MINOR 2
#define LEP_VERSION_PATCH 0
#define LEP_VERSION_STRING "0.2.0"
/* Compare with LEP_VERSION_NUMBER >= LEP_MAKE_VERSION(0, 1, 0). */
#define LEP_MAKE_VERSION(major, minor, patch) ((major)*10000L + (minor)*100L + (patch))
#define LEP_VERSION_NUMBER LEP_MAKE_VERSION(LEP_VERSION_MAJOR, LEP_VERSION_MINOR, LEP_VERSION_PATCH)

#endif
