/*
 * video.c: an MP4 (H.264) video written frame by frame with Debian's FFmpeg
 * libraries (oit.h, "video"): libavformat's MP4 muxer, libavcodec's libx264
 * encoder, libswscale for RGBA -> YUV 4:2:0. The file is written to a
 * temporary beside its name (oit_temporary_create) and renamed over it by
 * oit_video_close(keep = true), so a failed or cancelled video leaves the
 * previous file, or nothing, and no temporary.
 *
 * The libraries rather than the ffmpeg program: no process to start, find or
 * feed through a pipe; every failure is a status and a line here; each frame
 * is a call, so the caller reports progress and can stop between frames.
 *
 * The libraries are opened on the first video (dlopen, by the sonames of the
 * headers built against), not linked: linked, they and their ~110 codec
 * libraries loaded into every `oit` and workbench process, ~0.26 s more per
 * start and past a tight `ulimit -v` (tests/driver_failure.sh), for the few
 * runs that write a video.
 */
#define _POSIX_C_SOURCE 200809L
#include <dlfcn.h>
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/error.h>
#include <libavutil/imgutils.h>
#include <libavutil/log.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "oit.h"

/* The functions this file calls, from the libraries opened at run time
 * (LIBRARY: libavutil, libavcodec, libavformat, libswscale). */
#define FFMPEG_FUNCTIONS(X) \
    X(0, av_strerror) \
    X(0, av_log_set_level) \
    X(0, av_frame_alloc) \
    X(0, av_frame_free) \
    X(0, av_frame_get_buffer) \
    X(0, av_frame_make_writable) \
    X(0, av_opt_set) \
    X(1, avcodec_find_encoder_by_name) \
    X(1, avcodec_alloc_context3) \
    X(1, avcodec_free_context) \
    X(1, avcodec_open2) \
    X(1, avcodec_parameters_from_context) \
    X(1, avcodec_send_frame) \
    X(1, avcodec_receive_packet) \
    X(1, av_packet_alloc) \
    X(1, av_packet_free) \
    X(1, av_packet_rescale_ts) \
    X(2, avformat_alloc_output_context2) \
    X(2, avformat_free_context) \
    X(2, avformat_new_stream) \
    X(2, avformat_write_header) \
    X(2, av_interleaved_write_frame) \
    X(2, av_write_trailer) \
    X(2, avio_open) \
    X(2, avio_closep) \
    X(3, sws_getContext) \
    X(3, sws_freeContext) \
    X(3, sws_scale)

static struct {
#define FFMPEG_POINTER(LIBRARY, FUNCTION) __typeof__(&FUNCTION) FUNCTION;
    FFMPEG_FUNCTIONS(FFMPEG_POINTER)
#undef FFMPEG_POINTER
} ffmpeg;
static char ffmpeg_problem[512]; /* empty once every function is found */
static pthread_once_t ffmpeg_once = PTHREAD_ONCE_INIT;

static void ffmpeg_open(void)
{
    /* the sonames of the headers this file is built against */
    static const char *const sonames[4] = {
        "libavutil.so." AV_STRINGIFY(LIBAVUTIL_VERSION_MAJOR),
        "libavcodec.so." AV_STRINGIFY(LIBAVCODEC_VERSION_MAJOR),
        "libavformat.so." AV_STRINGIFY(LIBAVFORMAT_VERSION_MAJOR),
        "libswscale.so." AV_STRINGIFY(LIBSWSCALE_VERSION_MAJOR),
    };
    void *handles[4];
    for (int i = 0; i < 4; ++i) {
        handles[i] = dlopen(sonames[i], RTLD_NOW | RTLD_LOCAL);
        if (!handles[i]) {
            const char *why = dlerror();
            snprintf(ffmpeg_problem, sizeof ffmpeg_problem, "cannot load FFmpeg's %s: %s", sonames[i],
                     why ? why : "not found");
            return;
        }
    }
#define FFMPEG_FIND(LIBRARY, FUNCTION)                                                                          \
    {                                                                                                           \
        void *symbol = dlsym(handles[LIBRARY], #FUNCTION);                                                      \
        if (!symbol) {                                                                                          \
            snprintf(ffmpeg_problem, sizeof ffmpeg_problem, "%s has no %s", sonames[LIBRARY], #FUNCTION);      \
            return;                                                                                             \
        }                                                                                                       \
        memcpy(&ffmpeg.FUNCTION, &symbol, sizeof symbol);                                                       \
    }
    FFMPEG_FUNCTIONS(FFMPEG_FIND)
#undef FFMPEG_FIND
}

static oit_status ffmpeg_ready(const char *path, oit_error *err)
{
    pthread_once(&ffmpeg_once, ffmpeg_open);
    if (ffmpeg_problem[0])
        return oit_fail(err, OIT_E_RUNTIME, "video %s: %s", path, ffmpeg_problem);
    return OIT_OK;
}

/* the calls below go through the table */
#define av_strerror ffmpeg.av_strerror
#define av_log_set_level ffmpeg.av_log_set_level
#define av_frame_alloc ffmpeg.av_frame_alloc
#define av_frame_free ffmpeg.av_frame_free
#define av_frame_get_buffer ffmpeg.av_frame_get_buffer
#define av_frame_make_writable ffmpeg.av_frame_make_writable
#define av_opt_set ffmpeg.av_opt_set
#define avcodec_find_encoder_by_name ffmpeg.avcodec_find_encoder_by_name
#define avcodec_alloc_context3 ffmpeg.avcodec_alloc_context3
#define avcodec_free_context ffmpeg.avcodec_free_context
#define avcodec_open2 ffmpeg.avcodec_open2
#define avcodec_parameters_from_context ffmpeg.avcodec_parameters_from_context
#define avcodec_send_frame ffmpeg.avcodec_send_frame
#define avcodec_receive_packet ffmpeg.avcodec_receive_packet
#define av_packet_alloc ffmpeg.av_packet_alloc
#define av_packet_free ffmpeg.av_packet_free
#define av_packet_rescale_ts ffmpeg.av_packet_rescale_ts
#define avformat_alloc_output_context2 ffmpeg.avformat_alloc_output_context2
#define avformat_free_context ffmpeg.avformat_free_context
#define avformat_new_stream ffmpeg.avformat_new_stream
#define avformat_write_header ffmpeg.avformat_write_header
#define av_interleaved_write_frame ffmpeg.av_interleaved_write_frame
#define av_write_trailer ffmpeg.av_write_trailer
#define avio_open ffmpeg.avio_open
#define avio_closep ffmpeg.avio_closep
#define sws_getContext ffmpeg.sws_getContext
#define sws_freeContext ffmpeg.sws_freeContext
#define sws_scale ffmpeg.sws_scale

struct oit_video {
    oit_temporary temporary;
    char *path;
    int width, height;
    int64_t next_pts;
    AVFormatContext *format;
    AVCodecContext *codec;
    AVStream *stream;
    AVFrame *frame;
    AVPacket *packet;
    struct SwsContext *scale;
    bool header_written;
};

static oit_status av_failure(oit_error *err, const char *path, const char *what, int code)
{
    char reason[AV_ERROR_MAX_STRING_SIZE] = "";
    av_strerror(code, reason, sizeof reason);
    return oit_fail(err, OIT_E_RUNTIME, "video %s: %s: %s", path, what, reason);
}

static void video_free(oit_video *v, bool remove)
{
    if (!v)
        return;
    if (v->format) {
        if (v->format->pb)
            avio_closep(&v->format->pb);
        avformat_free_context(v->format);
    }
    avcodec_free_context(&v->codec);
    av_frame_free(&v->frame);
    av_packet_free(&v->packet);
    sws_freeContext(v->scale);
    oit_temporary_release(&v->temporary, remove);
    free(v->path);
    free(v);
}

oit_status oit_video_check_size(int width, int height, oit_error *err)
{
    if (width < 2 || height < 2 || width % 2 || height % 2 || width > 16384 || height > 16384)
        return oit_fail(err, OIT_E_INPUT,
                        "an H.264 video in yuv420p needs an even width and height from 2 to 16384, got %dx%d", width,
                        height);
    return OIT_OK;
}

oit_status oit_video_open(const char *path, int width, int height, int fps, oit_video **out, oit_error *err)
{
    *out = NULL;
    oit_status status = oit_video_check_size(width, height, err);
    if (status != OIT_OK)
        return status;
    if (fps < 1 || fps > OIT_VIDEO_FPS_MAX)
        return oit_fail(err, OIT_E_INPUT, "a video's frame rate must be 1 to %d frames per second, got %d",
                        OIT_VIDEO_FPS_MAX, fps);
    if ((status = ffmpeg_ready(path, err)) != OIT_OK)
        return status;
    /* the libraries print nothing: every failure comes back as a status */
    av_log_set_level(AV_LOG_QUIET);
    const AVCodec *encoder = avcodec_find_encoder_by_name("libx264");
    if (!encoder)
        return oit_fail(err, OIT_E_RUNTIME, "video %s: this libavcodec has no libx264 encoder", path);
    oit_video *v = calloc(1, sizeof *v);
    if (!v || !(v->path = strdup(path))) {
        free(v);
        return oit_fail(err, OIT_E_RUNTIME, "video %s: out of memory", path);
    }
    v->temporary.fd = v->temporary.watch = -1;
    v->width = width;
    v->height = height;
    oit_error temp_err;
    if (oit_temporary_create(path, false, &v->temporary, &temp_err) != OIT_OK) {
        video_free(v, true);
        return oit_fail(err, OIT_E_INPUT, "video %s: cannot write: %s", path, temp_err.message);
    }
    int code = avformat_alloc_output_context2(&v->format, NULL, "mp4", v->temporary.path);
    if (code < 0) {
        video_free(v, true);
        return av_failure(err, path, "cannot make an MP4 muxer", code);
    }
    v->stream = avformat_new_stream(v->format, NULL);
    v->codec = avcodec_alloc_context3(encoder);
    v->frame = av_frame_alloc();
    v->packet = av_packet_alloc();
    if (!v->stream || !v->codec || !v->frame || !v->packet) {
        video_free(v, true);
        return oit_fail(err, OIT_E_RUNTIME, "video %s: out of memory", path);
    }
    v->codec->width = width;
    v->codec->height = height;
    v->codec->pix_fmt = AV_PIX_FMT_YUV420P; /* what every player decodes */
    v->codec->time_base = (AVRational){1, fps};
    v->codec->framerate = (AVRational){fps, 1};
    v->codec->gop_size = fps;
    v->codec->thread_count = 1; /* one core: the renderer has the others, and the bytes do not vary */
    if (v->format->oformat->flags & AVFMT_GLOBALHEADER)
        v->codec->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
    av_opt_set(v->codec->priv_data, "preset", "medium", 0);
    av_opt_set(v->codec->priv_data, "crf", "18", 0); /* visually lossless for renders */
    code = avcodec_open2(v->codec, encoder, NULL);
    if (code < 0) {
        video_free(v, true);
        return av_failure(err, path, "cannot open the H.264 encoder", code);
    }
    code = avcodec_parameters_from_context(v->stream->codecpar, v->codec);
    v->stream->time_base = v->codec->time_base;
    v->frame->format = AV_PIX_FMT_YUV420P;
    v->frame->width = width;
    v->frame->height = height;
    if (code >= 0)
        code = av_frame_get_buffer(v->frame, 0);
    if (code < 0) {
        video_free(v, true);
        return av_failure(err, path, "cannot set up the frames", code);
    }
    /* RGBA -> YUV 4:2:0 in BT.601 limited range (swscale's default, what
     * players assume for this size without colour tags) */
    v->scale = sws_getContext(width, height, AV_PIX_FMT_RGBA, width, height, AV_PIX_FMT_YUV420P,
                              SWS_BICUBIC | SWS_ACCURATE_RND | SWS_FULL_CHR_H_INT, NULL, NULL, NULL);
    if (!v->scale) {
        video_free(v, true);
        return oit_fail(err, OIT_E_RUNTIME, "video %s: cannot make the RGBA to YUV converter", path);
    }
    code = avio_open(&v->format->pb, v->temporary.path, AVIO_FLAG_WRITE);
    if (code < 0) {
        video_free(v, true);
        return av_failure(err, path, "cannot write", code);
    }
    code = avformat_write_header(v->format, NULL);
    if (code < 0) {
        video_free(v, true);
        return av_failure(err, path, "cannot write the MP4 header", code);
    }
    v->header_written = true;
    *out = v;
    return OIT_OK;
}

/* Sends frame (NULL: flush) and writes every packet the encoder gives back. */
static oit_status encode(oit_video *v, AVFrame *frame, oit_error *err)
{
    int code = avcodec_send_frame(v->codec, frame);
    if (code < 0)
        return av_failure(err, v->path, "the H.264 encoder refused a frame", code);
    for (;;) {
        code = avcodec_receive_packet(v->codec, v->packet);
        if (code == AVERROR(EAGAIN) || code == AVERROR_EOF)
            return OIT_OK;
        if (code < 0)
            return av_failure(err, v->path, "the H.264 encoder failed", code);
        av_packet_rescale_ts(v->packet, v->codec->time_base, v->stream->time_base);
        v->packet->stream_index = v->stream->index;
        code = av_interleaved_write_frame(v->format, v->packet);
        if (code < 0)
            return av_failure(err, v->path, "cannot write", code);
    }
}

oit_status oit_video_write(oit_video *v, const oit_image *image, oit_error *err)
{
    if (image->width != v->width || image->height != v->height)
        return oit_fail(err, OIT_E_INPUT, "video %s: a frame of %dx%d in a video of %dx%d", v->path, image->width,
                        image->height, v->width, v->height);
    int code = av_frame_make_writable(v->frame);
    if (code < 0)
        return av_failure(err, v->path, "cannot reuse the frame", code);
    const uint8_t *source[1] = {image->rgba};
    const int stride[1] = {image->width * 4};
    sws_scale(v->scale, source, stride, 0, image->height, v->frame->data, v->frame->linesize);
    v->frame->pts = v->next_pts++;
    return encode(v, v->frame, err);
}

oit_status oit_video_close(oit_video *v, bool keep, oit_error *err)
{
    if (!v)
        return OIT_OK;
    oit_status status = OIT_OK;
    if (keep) {
        status = encode(v, NULL, err);
        int code = status == OIT_OK ? av_write_trailer(v->format) : 0;
        if (code < 0)
            status = av_failure(err, v->path, "cannot finish the MP4 file", code);
        if (status == OIT_OK) {
            code = avio_closep(&v->format->pb);
            if (code < 0)
                status = av_failure(err, v->path, "cannot write", code);
        }
        if (status == OIT_OK && fsync(v->temporary.fd) != 0)
            status = oit_fail(err, OIT_E_RUNTIME, "video %s: cannot write: %s", v->path, "fsync failed");
        if (status == OIT_OK && rename(v->temporary.path, v->path) != 0)
            status = oit_fail(err, OIT_E_RUNTIME, "video %s: cannot rename its temporary to it", v->path);
    }
    video_free(v, status != OIT_OK || !keep);
    return status;
}
