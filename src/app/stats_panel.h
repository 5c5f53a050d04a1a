// stats_panel.h: the settings panel's Stats tab: the last full frame's
// statistics (times, stages, memory, fragments, lists, layers), split side B's
// and the figures against the reference.
#pragma once

#include <QPlainTextEdit>
#include <QString>

#include "oit.h"
#include "settings.h"

class RenderView;

class StatsPanel : public QPlainTextEdit {
    Q_OBJECT
public:
    explicit StatsPanel(QWidget *parent = nullptr);

    // The view's last full frame, rendered with settings of model, in words:
    // the tab's text, and what the Compare tab and the status line show of it.
    struct Summary {
        QString text;        // this tab's (show it with setPlainText)
        double gpu_ms = 0.0; // the stages' sum
        QString figures;     // each side against the reference (the error view), one per line
        QString compared;    // the status line's tail: " — vs reference: ...", " | B ..."
    };
    static Summary describe(const RenderView &view, const RenderSettings &settings, const oit_model *model);
};
