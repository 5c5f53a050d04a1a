// algorithm_switcher.cpp: see algorithm_switcher.h.
#include "algorithm_switcher.h"

#include <QKeyEvent>
#include <QLabel>
#include <QLineEdit>
#include <QListWidget>
#include <QVBoxLayout>

#include "oit.h"

AlgorithmSwitcher::AlgorithmSwitcher(const QString &current, QWidget *parent) : QDialog(parent)
{
    setObjectName("algorithm_switcher");
    setWindowTitle("Switch algorithm");
    auto *layout = new QVBoxLayout(this);
    filter_ = new QLineEdit;
    filter_->setObjectName("algorithm_filter");
    filter_->setPlaceholderText("type to filter: name or summary");
    filter_->setToolTip("the algorithms whose name or summary contain the text; Enter chooses the selected one");
    list_ = new QListWidget;
    list_->setObjectName("algorithm_list");
    list_->setToolTip("every algorithm of the core's list (oit algorithms); Enter or a double-click chooses");
    size_t count;
    const oit_algorithm_ops *const *algorithms = oit_algorithm_list(&count);
    for (size_t i = 0; i < count; ++i) {
        auto *item = new QListWidgetItem(QString("%1 — %2").arg(algorithms[i]->name, algorithms[i]->summary), list_);
        item->setData(Qt::UserRole, QString(algorithms[i]->name));
        item->setToolTip(QString("%1 (%2)").arg(algorithms[i]->summary, algorithms[i]->exact ? "exact" : "approximate"));
        if (current == algorithms[i]->name)
            list_->setCurrentItem(item);
    }
    layout->addWidget(filter_);
    layout->addWidget(list_);
    resize(560, 360);
    connect(filter_, &QLineEdit::textChanged, this, &AlgorithmSwitcher::apply_filter);
    connect(filter_, &QLineEdit::returnPressed, this, &AlgorithmSwitcher::choose);
    connect(list_, &QListWidget::itemActivated, this, &AlgorithmSwitcher::choose);
    filter_->installEventFilter(this); // Up and Down move in the list while typing
    setAttribute(Qt::WA_DeleteOnClose);
}

QStringList AlgorithmSwitcher::shown() const
{
    QStringList names;
    for (int i = 0; i < list_->count(); ++i)
        if (!list_->item(i)->isHidden())
            names << list_->item(i)->data(Qt::UserRole).toString();
    return names;
}

void AlgorithmSwitcher::apply_filter(const QString &text)
{
    QListWidgetItem *first = nullptr;
    for (int i = 0; i < list_->count(); ++i) {
        QListWidgetItem *item = list_->item(i);
        // a name that starts with the text first: "d" finds dp before blend's summary
        bool match = item->text().contains(text.trimmed(), Qt::CaseInsensitive);
        item->setHidden(!match);
        if (match && (!first || (item->data(Qt::UserRole).toString().startsWith(text.trimmed(), Qt::CaseInsensitive) &&
                                 !first->data(Qt::UserRole).toString().startsWith(text.trimmed(), Qt::CaseInsensitive))))
            first = item;
    }
    if (!list_->currentItem() || list_->currentItem()->isHidden() ||
        (first && first != list_->currentItem() && !text.trimmed().isEmpty()))
        list_->setCurrentItem(first);
}

void AlgorithmSwitcher::choose()
{
    QListWidgetItem *item = list_->currentItem();
    if (!item || item->isHidden())
        return;
    emit chosen(item->data(Qt::UserRole).toString());
    accept();
}

bool AlgorithmSwitcher::eventFilter(QObject *watched, QEvent *event)
{
    if (watched == filter_ && event->type() == QEvent::KeyPress) {
        auto *key = static_cast<QKeyEvent *>(event);
        if (key->key() == Qt::Key_Up || key->key() == Qt::Key_Down) {
            int row = list_->currentRow();
            int step = key->key() == Qt::Key_Down ? 1 : -1;
            for (int r = row + step; r >= 0 && r < list_->count(); r += step)
                if (!list_->item(r)->isHidden()) {
                    list_->setCurrentRow(r);
                    break;
                }
            return true;
        }
    }
    return QDialog::eventFilter(watched, event);
}
