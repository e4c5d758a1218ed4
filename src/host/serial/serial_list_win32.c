/* Port discovery on Windows: the COM ports with their USB identity.
 *
 * SetupAPI lists the present devices of the COM port interface class
 * (GUID_DEVINTERFACE_COMPORT, {86E0D1E0-8089-11D0-9CE4-08003E301F73} in
 * Microsoft's docs); each one's "PortName" value in its device registry key
 * (SetupDiOpenDevRegKey, DIREG_DEV) is its COM name, its device instance ID
 * (SetupDiGetDeviceInstanceId) carries the USB identity ("USB\VID_0483&
 * PID_5740\...", FTDI's driver "FTDIBUS\VID_0403+PID_6001+..."), and its
 * friendly name the description. Ports that only the registry's
 * HKLM\HARDWARE\DEVICEMAP\SERIALCOMM lists (no interface: Wine's, some
 * virtual ports) are added without an identity. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <windows.h>
#include <setupapi.h>

#include "leptrino/error.h"
#include "leptrino/serial.h"
#include "struct_api.h"

static const GUID comport_interface = {
    0x86E0D1E0, 0x8089, 0x11D0, { 0x9C, 0xE4, 0x08, 0x00, 0x3E, 0x30, 0x1F, 0x73 }
};

static bool is_likely_sensor(uint16_t vid, uint16_t pid)
{
    return (vid == 0x0483 && pid == 0x5740) || (vid == 0x0403 && pid == 0x6001);
}

/* The four hex digits after key ("VID_") in id, or 0. */
static uint16_t hex_after(const char *id, const char *key)
{
    const char *p = strstr(id, key);
    unsigned v = 0;
    int i;
    if (p == NULL)
        return 0;
    p += strlen(key);
    for (i = 0; i < 4; i++) {
        char c = p[i];
        unsigned d;
        if (c >= '0' && c <= '9')
            d = (unsigned)(c - '0');
        else if (c >= 'A' && c <= 'F')
            d = (unsigned)(c - 'A' + 10);
        else if (c >= 'a' && c <= 'f')
            d = (unsigned)(c - 'a' + 10);
        else
            return 0;
        v = v * 16u + d;
    }
    return (uint16_t)v;
}

/* "COM12" -> 12, for sorting; other names after every COMn. */
static unsigned long com_number(const char *name)
{
    if ((name[0] == 'C' || name[0] == 'c') && (name[1] == 'O' || name[1] == 'o') &&
        (name[2] == 'M' || name[2] == 'm') && name[3] >= '0' && name[3] <= '9')
        return strtoul(name + 3, NULL, 10);
    return 0xFFFFFFFFul;
}

static int by_number(const void *a, const void *b)
{
    const lep_port_info *x = a, *y = b;
    unsigned long m = com_number(x->path), n = com_number(y->path);
    if (m != n)
        return m < n ? -1 : 1;
    return strcmp(x->path, y->path);
}

static bool listed(const lep_port_info *out, size_t count, size_t max, const char *name)
{
    size_t i;
    for (i = 0; i < count && i < max; i++)
        if (_stricmp(out[i].path, name) == 0)
            return true;
    return false;
}

/* A string value of an open key into out (NUL-terminated), or false. */
static bool reg_string(HKEY key, const char *name, char *out, DWORD cap)
{
    DWORD type = 0, size = cap - 1;
    if (RegQueryValueExA(key, name, NULL, &type, (BYTE *)out, &size) != ERROR_SUCCESS ||
        type != REG_SZ)
        return false;
    out[size < cap ? size : cap - 1] = '\0';
    return out[0] != '\0';
}

static void add(lep_port_info *out, size_t max, size_t *count, const char *name, const char *id,
                const char *description)
{
    if (*count < max) {
        lep_port_info *p = &out[*count];
        memset(p, 0, sizeof *p);
        snprintf(p->path, sizeof p->path, "%s", name);
        snprintf(p->description, sizeof p->description, "%s", description);
        if (id != NULL) {
            p->vid = hex_after(id, "VID_");
            p->pid = hex_after(id, "PID_");
            p->likely_sensor = is_likely_sensor(p->vid, p->pid);
        }
    }
    (*count)++;
}

static void list_setupapi(lep_port_info *out, size_t max, size_t *count)
{
    HDEVINFO set =
        SetupDiGetClassDevsA(&comport_interface, NULL, NULL, DIGCF_PRESENT | DIGCF_DEVICEINTERFACE);
    SP_DEVINFO_DATA dev;
    DWORD i;
    if (set == INVALID_HANDLE_VALUE)
        return;
    for (i = 0;; i++) {
        char name[64], id[512], desc[128];
        HKEY key;
        bool named;
        memset(&dev, 0, sizeof dev);
        dev.cbSize = sizeof dev;
        if (!SetupDiEnumDeviceInfo(set, i, &dev))
            break;
        key = SetupDiOpenDevRegKey(set, &dev, DICS_FLAG_GLOBAL, 0, DIREG_DEV, KEY_READ);
        if (key == INVALID_HANDLE_VALUE)
            continue;
        named = reg_string(key, "PortName", name, sizeof name);
        RegCloseKey(key);
        if (!named || listed(out, *count, max, name))
            continue;
        if (!SetupDiGetDeviceInstanceIdA(set, &dev, id, sizeof id, NULL))
            id[0] = '\0';
        if (!SetupDiGetDeviceRegistryPropertyA(set, &dev, SPDRP_FRIENDLYNAME, NULL, (BYTE *)desc,
                                               sizeof desc, NULL) &&
            !SetupDiGetDeviceRegistryPropertyA(set, &dev, SPDRP_DEVICEDESC, NULL, (BYTE *)desc,
                                               sizeof desc, NULL))
            desc[0] = '\0';
        desc[sizeof desc - 1] = '\0';
        add(out, max, count, name, id, desc);
    }
    SetupDiDestroyDeviceInfoList(set);
}

static void list_serialcomm(lep_port_info *out, size_t max, size_t *count)
{
    HKEY key;
    DWORD i;
    if (RegOpenKeyExA(HKEY_LOCAL_MACHINE, "HARDWARE\\DEVICEMAP\\SERIALCOMM", 0, KEY_READ, &key) !=
        ERROR_SUCCESS)
        return;
    for (i = 0;; i++) {
        char value[256], data[64];
        DWORD vlen = sizeof value, dlen = sizeof data - 1, type = 0;
        LONG r = RegEnumValueA(key, i, value, &vlen, NULL, &type, (BYTE *)data, &dlen);
        if (r == ERROR_NO_MORE_ITEMS)
            break;
        if (r != ERROR_SUCCESS || type != REG_SZ)
            continue;
        data[dlen < sizeof data ? dlen : sizeof data - 1] = '\0';
        if (data[0] == '\0' || listed(out, *count, max, data))
            continue;
        add(out, max, count, data, NULL, "");
    }
    RegCloseKey(key);
}

int lep_serial_list(lep_port_info *out, size_t max, size_t *n)
{
    size_t count = 0;
    if (n == NULL || (out == NULL && max > 0))
        return LEP_E_ARG;
    *n = 0;
    list_setupapi(out, max, &count);
    list_serialcomm(out, max, &count);
    if (out != NULL)
        qsort(out, count < max ? count : max, sizeof *out, by_number);
    *n = count;
    return LEP_OK;
}
