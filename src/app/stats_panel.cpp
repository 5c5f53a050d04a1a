// stats_panel.cpp: see stats_panel.h.
#include "stats_panel.h"
#include "error_legend.h"
#include "render_view.h"

#include <QFontDatabase>
#include <QTextStream>

StatsPanel::StatsPanel(QWidget *parent) : QPlainTextEdit(parent)
{
    setReadOnly(true);
    setFont(QFontDatabase::systemFont(QFontDatabase::FixedFont));
}

StatsPanel::Summary StatsPanel::describe(const RenderView &view, const RenderSettings &settings,
                                         const oit_model *model)
{
    Summary summary;
    const oit_stats &st = view.last_stats();
    QString text;
    QTextStream out(&text);
    double gpu_total = 0.0;
    for (int i = 0; i < st.stage_count; ++i)
        gpu_total += st.stages[i].gpu_ms;
    summary.gpu_ms = gpu_total;
    QSize size = view.last_image().size();
    out << QString("%1, %2x%3\n").arg(QString::fromStdString(settings.algorithm)).arg(size.width()).arg(size.height());
    out << QString("%1 frame time (CPU)   %2 ms\n").arg("", 0).arg(st.cpu_ms, 0, 'f', 2);
    out << QString("frames per second   %1%2\n")
               .arg(view.measured_fps(), 0, 'f', 1)
               .arg(QString("")); // continuous rendering (F) measures it; otherwise 1 / frame time
    out << QString("stages (GPU)        %1 ms\n").arg(gpu_total, 0, 'f', 2);
    for (int i = 0; i < st.stage_count && i < 40; ++i)
        out << QString("  %1 %2 ms\n").arg(QString(st.stages[i].name), -18).arg(st.stages[i].gpu_ms, 8, 'f', 3);
    if (st.stage_count > 40)
        out << QString("  ... %1 stages in all\n").arg(st.stage_count);
    out << QString("memory              %1 MB\n").arg(double(st.memory_bytes) / (1024.0 * 1024.0), 0, 'f', 2);
    auto optional = [&out](const char *name, int64_t value) {
        if (value >= 0)
            out << QString("%1 %2\n").arg(name, -19).arg(qlonglong(value));
    };
    optional("fragments", st.fragments);
    optional("longest list", st.max_list);
    optional("layers", st.layers);
    if (st.truncated)
        out << QString("TRUNCATED           the layer cap %1 left fragments out\n").arg(settings.config.max_layers);
    if (st.mean_list >= 0)
        out << QString("mean list           %1\n").arg(st.mean_list, 0, 'f', 2);
    if (st.psi >= 0)
        out << QString("psi (lists > 2/3 max) %1\n").arg(st.psi, 0, 'f', 4);
    if (st.overflow_retries >= 0)
        out << QString("overflow events     %1 this frame, %2 in all\n")
                   .arg(qlonglong(st.overflow_retries))
                   .arg(view.total_overflow_retries());
    if (st.bands > 1)
        out << QString("bands of rows       %1 (more fragments than one pool holds)\n").arg(qlonglong(st.bands));
    if (st.bytes_per_fragment > 0)
        out << QString("bytes / fragment    %1\n").arg(st.bytes_per_fragment, 0, 'f', 1);
    if (st.neighbours_four_share >= 0)
        out << QString("four neighbours     %1\n").arg(st.neighbours_four_share, 0, 'f', 3);
    if (model)
        out << QString("model               %1 triangles, %2 parts\n").arg(model->triangle_count).arg(model->component_count);
    out << QString("renderer            %1\n").arg(QString::fromStdString(view.renderer()));
    // the comparisons: side B and the error against the reference
    FrameResultPointer last = view.last_result();
    if (last && last->coarse_scale == 1 && settings.error_view) {
        auto describe = [](const std::string &name, const ErrorResult &e) {
            if (!e.present)
                return QString("%1 vs reference: %2").arg(QString::fromStdString(name), e.problem);
            return QString("%1 vs reference: %2 (reference %3, error %4 ms)")
                .arg(QString::fromStdString(name), error_figures_text(e.figures),
                     e.reference_cached ? QString("cached") : QString("%1 ms").arg(e.reference_ms, 0, 'f', 1))
                .arg(e.error_ms, 0, 'f', 1);
        };
        summary.figures = describe(last->algorithm, last->error_map);
        if (last->split && last->b.status == OIT_OK)
            summary.figures += "\n" + describe(last->b.algorithm, last->b.error_map);
        out << summary.figures << "\n";
        if (last->error_map.present)
            summary.compared += " — vs reference: " + error_figures_text(last->error_map.figures);
    }
    if (last && last->split) {
        const SideResult &b = last->b;
        if (b.status == OIT_OK)
            out << QString("split side B        %1: %2 ms CPU, %3 MB\n")
                       .arg(QString::fromStdString(b.algorithm))
                       .arg(b.stats.cpu_ms, 0, 'f', 2)
                       .arg(double(b.stats.memory_bytes) / (1024.0 * 1024.0), 0, 'f', 2);
        else
            out << QString("split side B        %1 failed: %2\n")
                       .arg(QString::fromStdString(b.algorithm), b.error);
        summary.compared +=
            QString(" | B %1: %2 ms").arg(QString::fromStdString(b.algorithm)).arg(b.stats.cpu_ms, 0, 'f', 1);
        if (settings.error_view && b.error_map.present)
            summary.compared += QString(", rmse %1").arg(b.error_map.figures.rmse, 0, 'f', 3);
    }
    out.flush();
    summary.text = text;
    return summary;
}
