/* shader_dir.c: find the shader tree at run time: $OIT_SHADER_DIR if set,
 * else next to the executable (installed: ../share/oit-workbench/shaders;
 * or ./shaders), else the source tree the binary was built from. */
#define _DEFAULT_SOURCE /* readlink, realpath */
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "oit.h"

#ifndef OIT_SOURCE_SHADER_DIR
#define OIT_SOURCE_SHADER_DIR ""
#endif
#ifndef OIT_INSTALL_SHADER_SUBDIR
#define OIT_INSTALL_SHADER_SUBDIR "share/oit-workbench/shaders"
#endif

#define PATH_SIZE 4096

/* A shader tree is valid if it holds the shared C/GLSL header. */
static bool is_shader_dir(const char *dir)
{
    char marker[PATH_SIZE + 32];
    snprintf(marker, sizeof marker, "%.4000s/common/oit_shared.h", dir);
    return access(marker, R_OK) == 0;
}

/* The directory of the running executable: /proc/self/exe, else argv[0]. */
static bool executable_dir(const char *argv0, char *out, size_t out_size)
{
    char path[PATH_SIZE];
    ssize_t length = readlink("/proc/self/exe", path, sizeof path - 1);
    if (length > 0) {
        path[length] = '\0';
    } else if (argv0 && strchr(argv0, '/') && strlen(argv0) < sizeof path) {
        snprintf(path, sizeof path, "%s", argv0);
    } else {
        return false;
    }
    char *slash = strrchr(path, '/');
    if (!slash)
        return false;
    if (slash == path)
        slash[1] = '\0'; /* executable in / */
    else
        *slash = '\0';
    snprintf(out, out_size, "%s", path);
    return true;
}

/* Every file in the tree must be a regular file: the shader loader reads
 * files whole, and a FIFO or a device would block it or never end. The
 * first other one is named (exit status 3, as a missing shader). */
static oit_status check_shader_tree(const char *dir, int depth, oit_error *err)
{
    if (depth > 8) /* a tree that deep is a link loop */
        return OIT_OK;
    DIR *listing = opendir(dir);
    if (!listing)
        return OIT_OK; /* what cannot be listed is named when a shader is read from it */
    oit_status status = OIT_OK;
    struct dirent *entry;
    while (status == OIT_OK && (entry = readdir(listing))) {
        const char *name = entry->d_name;
        if (strcmp(name, ".") == 0 || strcmp(name, "..") == 0)
            continue;
        char path[PATH_SIZE];
        if (snprintf(path, sizeof path, "%s/%s", dir, name) >= (int)sizeof path)
            continue;
        struct stat info;
        if (stat(path, &info) != 0)
            continue; /* a dangling link: named when read */
        if (S_ISDIR(info.st_mode))
            status = check_shader_tree(path, depth + 1, err);
        else if (!S_ISREG(info.st_mode) && oit_check_regular_file(path, "shader file", err) != OIT_OK)
            status = OIT_E_RUNTIME;
    }
    closedir(listing);
    return status;
}

oit_status oit_find_shader_dir(const char *argv0, char *out, size_t out_size, oit_error *err)
{
    char candidates[4][PATH_SIZE];
    int count = 0;
    const char *from_environment = getenv("OIT_SHADER_DIR");
    if (from_environment && *from_environment) {
        /* An explicit choice is not second-guessed: a wrong one is an error. */
        if (!is_shader_dir(from_environment))
            return oit_fail(err, OIT_E_RUNTIME,
                            "OIT_SHADER_DIR=%.400s holds no shaders (no common/oit_shared.h there)",
                            from_environment);
        snprintf(candidates[count++], PATH_SIZE, "%s", from_environment);
    }
    char exe_dir[PATH_SIZE];
    if (executable_dir(argv0, exe_dir, sizeof exe_dir)) {
        snprintf(candidates[count++], PATH_SIZE, "%.3000s/../%s", exe_dir,
                 OIT_INSTALL_SHADER_SUBDIR);
        snprintf(candidates[count++], PATH_SIZE, "%.3000s/shaders", exe_dir);
    }
    if (*OIT_SOURCE_SHADER_DIR)
        snprintf(candidates[count++], PATH_SIZE, "%s", OIT_SOURCE_SHADER_DIR);

    for (int i = 0; i < count; ++i) {
        if (!is_shader_dir(candidates[i]))
            continue;
        char resolved[PATH_SIZE];
        const char *found = realpath(candidates[i], resolved) ? resolved : candidates[i];
        if (strlen(found) >= out_size)
            return oit_fail(err, OIT_E_RUNTIME, "shader directory path too long: %s", found);
        snprintf(out, out_size, "%s", found);
        return check_shader_tree(out, 0, err);
    }
    char tried[OIT_ERROR_MESSAGE_SIZE] = "";
    size_t used = 0;
    for (int i = 0; i < count && used < sizeof tried; ++i)
        used += (size_t)snprintf(tried + used, sizeof tried - used, "%s%s", i ? ", " : "",
                                 candidates[i]);
    return oit_fail(err, OIT_E_RUNTIME,
                    "no shader directory (common/oit_shared.h) found; tried: %s%s", tried,
                    count ? "" : "(nothing)");
}
