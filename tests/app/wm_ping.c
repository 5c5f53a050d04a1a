// wm_ping: does a window answer the window manager's _NET_WM_PING in time?
//
//   wm_ping --title SUBSTRING --duration SECONDS [--interval-ms 50] [--limit-ms 250]
//           [--wait-window SECONDS] [--json FILE]
//
// Desktops ping a window (EWMH _NET_WM_PING) and mark its application "not
// responding" when the answer is late: the answer comes from the client's
// event loop, so a GUI thread busy for seconds misses it. This probe plays
// that part of a window manager without being one: it waits for a window
// whose title contains SUBSTRING and that takes part in the protocol, pings
// it every interval for DURATION seconds and measures each answer.
//
// Prints one JSON line: {"window", "pings", "answered", "max_ms", "p50_ms",
// "p99_ms", "over_limit", "worst_at_s", "destroyed", "first_answer_ms"} (also written to --json FILE).
// The first ping (the window's start-up: its first paint) is answered before
// the measured ones start and reported apart as first_answer_ms.
// A ping never answered counts with the time it has waited so far.
// Exit: 0 every latency <= limit; 1 one was over (or the window went away
// before the end); 2 usage error (or --json not writable); 3 no window found
// or no X connection.
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <poll.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include <xcb/xcb.h>

typedef struct {
    double sent;     // seconds, monotonic clock
    double answered; // < 0: not (yet) answered
} Ping;

static xcb_connection_t *conn;
static xcb_window_t root;
static xcb_atom_t WM_PROTOCOLS, NET_WM_PING, NET_WM_NAME, UTF8_STRING;

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + (double)t.tv_nsec * 1e-9;
}

static int usage(const char *message)
{
    fprintf(stderr, "wm_ping: %s (usage: wm_ping --title SUBSTRING --duration SECONDS [--interval-ms MS] "
                    "[--limit-ms MS] [--wait-window SECONDS] [--json FILE])\n",
            message);
    return 2;
}

// a whole-string number in [low, high]
static bool number(const char *text, double low, double high, double *out)
{
    char *end;
    errno = 0;
    double value = strtod(text, &end);
    if (errno || end == text || *end || !(value >= low && value <= high))
        return false;
    *out = value;
    return true;
}

static xcb_atom_t intern(const char *name)
{
    xcb_intern_atom_reply_t *reply =
        xcb_intern_atom_reply(conn, xcb_intern_atom(conn, 0, (uint16_t)strlen(name), name), NULL);
    xcb_atom_t atom = reply ? reply->atom : XCB_ATOM_NONE;
    free(reply);
    return atom;
}

// the property's value, NUL-terminated (NULL if the window has none of that type)
static char *property(xcb_window_t window, xcb_atom_t name, xcb_atom_t type, int *length)
{
    xcb_get_property_reply_t *reply =
        xcb_get_property_reply(conn, xcb_get_property(conn, 0, window, name, type, 0, 4096), NULL);
    if (!reply || reply->type == XCB_ATOM_NONE) {
        free(reply);
        return NULL;
    }
    int n = xcb_get_property_value_length(reply);
    char *value = malloc((size_t)n + 1);
    if (value) {
        memcpy(value, xcb_get_property_value(reply), (size_t)n);
        value[n] = '\0';
        *length = n;
    }
    free(reply);
    return value;
}

static bool title_contains(xcb_window_t window, const char *needle)
{
    // _NET_WM_NAME is UTF-8; WM_NAME is Latin-1 or compound text (any type),
    // and either may be missing: the title matches if one of them does
    const xcb_atom_t names[2] = {NET_WM_NAME, XCB_ATOM_WM_NAME};
    const xcb_atom_t types[2] = {UTF8_STRING, XCB_GET_PROPERTY_TYPE_ANY};
    for (int i = 0; i < 2; ++i) {
        int n;
        char *title = property(window, names[i], types[i], &n);
        bool found = title && strstr(title, needle);
        free(title);
        if (found)
            return true;
    }
    return false;
}

static bool takes_ping(xcb_window_t window)
{
    int n;
    char *value = property(window, WM_PROTOCOLS, XCB_ATOM_ATOM, &n);
    bool found = false;
    for (int i = 0; value && i + 4 <= n; i += 4) {
        xcb_atom_t atom;
        memcpy(&atom, value + i, sizeof atom);
        found = found || atom == NET_WM_PING;
    }
    free(value);
    return found;
}

// depth-first from the root: without a window manager the client's window is
// a child of the root, under a reparenting one it is deeper
static xcb_window_t find_window(xcb_window_t parent, const char *needle, int depth)
{
    xcb_query_tree_reply_t *tree = xcb_query_tree_reply(conn, xcb_query_tree(conn, parent), NULL);
    if (!tree)
        return XCB_WINDOW_NONE;
    xcb_window_t *children = xcb_query_tree_children(tree);
    xcb_window_t found = XCB_WINDOW_NONE;
    for (int i = 0; i < xcb_query_tree_children_length(tree) && !found; ++i) {
        if (title_contains(children[i], needle) && takes_ping(children[i]))
            found = children[i];
        else if (depth < 3)
            found = find_window(children[i], needle, depth + 1);
    }
    free(tree);
    return found;
}

static int compare(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

int main(int argc, char **argv)
{
    const char *title = NULL, *json = NULL;
    double duration = -1, interval_ms = 50, limit_ms = 250, wait_s = 60;
    for (int i = 1; i < argc; ++i) {
        const char *flag = argv[i];
        if (i + 1 >= argc)
            return usage(strncmp(flag, "--", 2) ? "unexpected argument" : "an option without its value");
        const char *value = argv[++i];
        if (!strcmp(flag, "--title"))
            title = value;
        else if (!strcmp(flag, "--json"))
            json = value;
        else if (!strcmp(flag, "--duration")) {
            if (!number(value, 0.001, 86400, &duration))
                return usage("--duration must be seconds in (0, 86400]");
        } else if (!strcmp(flag, "--interval-ms")) {
            if (!number(value, 1, 60000, &interval_ms))
                return usage("--interval-ms must be in [1, 60000]");
        } else if (!strcmp(flag, "--limit-ms")) {
            if (!number(value, 1, 3600000, &limit_ms))
                return usage("--limit-ms must be in [1, 3600000]");
        } else if (!strcmp(flag, "--wait-window")) {
            if (!number(value, 0, 86400, &wait_s))
                return usage("--wait-window must be seconds in [0, 86400]");
        } else {
            return usage("unknown option");
        }
    }
    if (!title || !*title || duration < 0)
        return usage("--title and --duration are required");

    int screen_number;
    conn = xcb_connect(NULL, &screen_number);
    if (xcb_connection_has_error(conn)) {
        fprintf(stderr, "wm_ping: cannot connect to the X display '%s'\n", getenv("DISPLAY") ? getenv("DISPLAY") : "");
        return 3;
    }
    xcb_screen_iterator_t screens = xcb_setup_roots_iterator(xcb_get_setup(conn));
    for (int i = 0; i < screen_number; ++i)
        xcb_screen_next(&screens);
    root = screens.data->root;
    WM_PROTOCOLS = intern("WM_PROTOCOLS");
    NET_WM_PING = intern("_NET_WM_PING");
    NET_WM_NAME = intern("_NET_WM_NAME");
    UTF8_STRING = intern("UTF8_STRING");

    xcb_window_t window = XCB_WINDOW_NONE;
    for (double give_up = now() + wait_s;;) {
        window = find_window(root, title, 0);
        if (window || now() >= give_up || xcb_connection_has_error(conn))
            break;
        nanosleep(&(struct timespec){0, 50 * 1000 * 1000}, NULL);
    }
    if (!window) {
        fprintf(stderr, "wm_ping: no window titled '*%s*' taking _NET_WM_PING within %g s\n", title, wait_s);
        return 3;
    }

    // Answers are sent to the root for clients that select SubstructureNotify
    // (EWMH) or StructureNotify (what Qt 5 sends with) there. Never
    // SubstructureRedirect: that is the window manager's, taking it would stop
    // the window from mapping. StructureNotify on the window itself says when
    // it is destroyed, with or without a window manager.
    xcb_change_window_attributes(conn, root, XCB_CW_EVENT_MASK,
                                 (uint32_t[]){XCB_EVENT_MASK_STRUCTURE_NOTIFY | XCB_EVENT_MASK_SUBSTRUCTURE_NOTIFY});
    xcb_change_window_attributes(conn, window, XCB_CW_EVENT_MASK, (uint32_t[]){XCB_EVENT_MASK_STRUCTURE_NOTIFY});
    xcb_flush(conn);

    // the serial in data32[1] identifies the ping; a base far from 0 keeps it
    // apart from the server timestamps a real window manager would use
    const uint32_t base = 0x40000000u | ((uint32_t)getpid() & 0xffffu) << 12;
    size_t count = 0, capacity = 256;
    Ping *pings = malloc(capacity * sizeof *pings);
    if (!pings)
        return 3;
    // One ping first, answered before the measured pings start: the window's
    // first answer waits for its first paint (fonts, style, layout), which is
    // the start-up of any Qt program, not the loading and rendering measured
    // here. How long it took is reported as first_answer_ms.
    double first_answer_ms = -1;
    {
        const uint32_t warm = base - 1;
        xcb_client_message_event_t ping = {
            .response_type = XCB_CLIENT_MESSAGE,
            .format = 32,
            .window = window,
            .type = WM_PROTOCOLS,
            .data.data32 = {NET_WM_PING, warm, window},
        };
        const double sent = now();
        xcb_send_event(conn, 0, window, XCB_EVENT_MASK_NO_EVENT, (const char *)&ping);
        xcb_flush(conn);
        while (first_answer_ms < 0 && now() < sent + wait_s && !xcb_connection_has_error(conn)) {
            struct pollfd fd = {xcb_get_file_descriptor(conn), POLLIN, 0};
            poll(&fd, 1, 50);
            xcb_generic_event_t *event;
            while ((event = xcb_poll_for_event(conn))) {
                xcb_client_message_event_t *reply = (xcb_client_message_event_t *)event;
                if ((event->response_type & 0x7f) == XCB_CLIENT_MESSAGE && reply->format == 32 &&
                    reply->data.data32[0] == NET_WM_PING && reply->data.data32[1] == warm)
                    first_answer_ms = (now() - sent) * 1000;
                free(event);
            }
        }
        if (first_answer_ms < 0) {
            fprintf(stderr, "wm_ping: the window never answered its first ping within %g s\n", wait_s);
            return 1;
        }
    }

    const double interval = interval_ms / 1000, limit = limit_ms / 1000;
    const double start = now(), end = start + duration;
    double next = start, drain_end = -1;
    bool destroyed = false, broken = false;
    size_t outstanding = 0;
    for (;;) {
        double t = now();
        if (t >= end) {
            // a ping sent just before the end still gets up to the limit to
            // be answered: an answer later than that is over it anyway
            if (drain_end < 0)
                drain_end = t + limit;
            if (t >= drain_end || outstanding == 0)
                break;
        } else if (t >= next) {
            if (count == capacity) {
                Ping *grown = realloc(pings, 2 * capacity * sizeof *pings);
                if (!grown)
                    break;
                pings = grown;
                capacity *= 2;
            }
            xcb_client_message_event_t ping = {
                .response_type = XCB_CLIENT_MESSAGE,
                .format = 32,
                .window = window,
                .type = WM_PROTOCOLS,
                .data.data32 = {NET_WM_PING, base + (uint32_t)count, window},
            };
            // no propagation, empty mask: delivered to the window's own client
            xcb_send_event(conn, 0, window, XCB_EVENT_MASK_NO_EVENT, (const char *)&ping);
            xcb_flush(conn);
            pings[count++] = (Ping){t, -1};
            ++outstanding;
            // a late probe does not burst to catch up
            next += interval;
            if (next < t)
                next = t + interval;
        }

        double wake = drain_end >= 0 ? drain_end : (next < end ? next : end);
        int timeout = (int)((wake - now()) * 1000) + 1;
        struct pollfd fd = {xcb_get_file_descriptor(conn), POLLIN, 0};
        if (poll(&fd, 1, timeout < 0 ? 0 : timeout) < 0 && errno != EINTR)
            break;
        xcb_generic_event_t *event;
        while ((event = xcb_poll_for_event(conn))) {
            uint8_t type = event->response_type & 0x7f;
            if (type == XCB_CLIENT_MESSAGE) {
                xcb_client_message_event_t *reply = (xcb_client_message_event_t *)event;
                uint32_t index = reply->data.data32[1] - base;
                if (reply->format == 32 && reply->type == WM_PROTOCOLS && reply->data.data32[0] == NET_WM_PING &&
                    reply->data.data32[2] == window && index < count && pings[index].answered < 0) {
                    pings[index].answered = now();
                    --outstanding;
                }
            } else if (type == XCB_DESTROY_NOTIFY && ((xcb_destroy_notify_event_t *)event)->window == window) {
                destroyed = true;
            } else if (type == 0 && ((xcb_generic_error_t *)event)->error_code == XCB_WINDOW &&
                       ((xcb_generic_error_t *)event)->resource_id == window) {
                destroyed = true; // a ping sent as the window went away
            }
            free(event);
        }
        if (xcb_connection_has_error(conn)) {
            broken = true;
            break;
        }
        if (destroyed)
            break;
    }
    const double stop = now();

    // latency of each ping; the unanswered ones with what they have waited so far
    double *latency = malloc((count ? count : 1) * sizeof *latency);
    if (!latency)
        return 3;
    size_t answered = 0, over = 0, worst = 0;
    for (size_t i = 0; i < count; ++i) {
        bool ok = pings[i].answered >= 0;
        answered += ok;
        latency[i] = ((ok ? pings[i].answered : stop) - pings[i].sent) * 1000;
        over += latency[i] > limit_ms;
        if (latency[i] > latency[worst])
            worst = i;
    }
    double max_ms = count ? latency[worst] : 0, worst_at = count ? pings[worst].sent - start : 0;
    qsort(latency, count, sizeof *latency, compare);
    // nearest rank
    double p50 = count ? latency[(count * 50 + 99) / 100 - 1] : 0;
    double p99 = count ? latency[(count * 99 + 99) / 100 - 1] : 0;

    char line[512];
    snprintf(line, sizeof line,
             "{\"window\": %u, \"pings\": %zu, \"answered\": %zu, \"max_ms\": %.1f, \"p50_ms\": %.1f, "
             "\"p99_ms\": %.1f, \"over_limit\": %zu, \"worst_at_s\": %.2f, \"destroyed\": %s, "
             "\"first_answer_ms\": %.1f}",
             (unsigned)window, count, answered, max_ms, p50, p99, over, worst_at, destroyed ? "true" : "false",
             first_answer_ms);
    puts(line);
    if (json) {
        FILE *file = fopen(json, "w");
        if (!file || fprintf(file, "%s\n", line) < 0 || fclose(file)) {
            fprintf(stderr, "wm_ping: cannot write %s\n", json);
            return 2;
        }
    }
    free(latency);
    free(pings);
    xcb_disconnect(conn);

    if (broken) {
        fprintf(stderr, "wm_ping: the X connection broke after %.1f s\n", stop - start);
        return 3;
    }
    if (over) {
        fprintf(stderr, "wm_ping: %zu of %zu pings over %g ms, worst %.0f ms (sent at %.2f s)\n", over, count,
                limit_ms, max_ms, worst_at);
        return 1;
    }
    if (destroyed) {
        fprintf(stderr, "wm_ping: the window was destroyed after %.1f s of %g\n", stop - start, duration);
        return 1;
    }
    return 0;
}
