/* Read by the size report (cmake/size_report.py), never linked: each array
 * is as large as one context, so `nm -S` on this object tells their sizes as
 * the target compiler lays them out. */
#include "leptrino/leptrino.h"

char lep_sizeof_lep_client[sizeof(lep_client)];
char lep_sizeof_lep_device[sizeof(lep_device)];
char lep_sizeof_lep_frame_decoder[sizeof(lep_frame_decoder)];
